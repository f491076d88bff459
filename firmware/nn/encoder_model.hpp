// What the encoder needs from a quantized model: pointers into the weight arrays of a
// generated header (firmware/nn/models/<name>_weights.hpp defines kEncoderModel) plus the
// zero points. Everything int8 is TFLite-style: real = scale·(q − zero_point).
#pragma once
#include <cstdint>

#include "firmware/nn/encoder_arch.hpp"

namespace curio::nn {

// A layer followed by ReLU, requantized per output channel.
struct QuantizedLayer {
  const int8_t* filter = nullptr;       // conv [32, 4, 4, C_in]; FC [out, in] (NHWC columns)
  const int32_t* bias = nullptr;        // scale s_in·s_w[c]
  const int32_t* multiplier = nullptr;  // Q31 of s_in·s_w[c]/s_out
  const int32_t* shift = nullptr;
  int32_t input_offset = 0;   // −zp_in
  int32_t output_offset = 0;  // +zp_out; ReLU clamps at it
};

// The last FC (20 rows: μ then log-variance) kept as int32 sums and dequantized
// in float: value[j] = scale[j]·(bias[j] + Σ (in + input_offset)·filter[j]). Its weights
// are int16 (±16,383): with int8 they were the largest single source of μ error, and the
// layer is small (10 KiB).
struct LatentLayer {
  const int16_t* filter = nullptr;  // [20, 256]
  const int32_t* bias = nullptr;    // [20]
  const float* scale = nullptr;     // [20] = s_in·s_w[j]
  int32_t input_offset = 0;
};

inline constexpr int32_t kLatentOutputs = 2 * kLatents;

struct EncoderModel {
  QuantizedLayer conv[kConvLayers];
  QuantizedLayer fc1;  // 512 → 256
  QuantizedLayer fc2;  // 256 → 256
  LatentLayer latent;  // 256 → 20
};

// The image enters as q = pixel − 128 with scale 1/255 (zero point −128), so conv[0]'s
// input_offset is always this.
inline constexpr int32_t kImageInputOffset = 128;

}  // namespace curio::nn
