// The β-VAE encoder on a camera frame, int8, in one static arena (no heap, no OS).
//
// Input: 64×64×3 uint8 RGB, HWC, row 0 at the top (what the camera sends; a rendered
// float image v becomes round(255·v)). Output: μ (and optionally log σ²) of the 10
// latents as float, dequantized from the last layer's int32 sums so the int8 path adds
// no rounding there.
#pragma once
#include <cstdint>

#include "firmware/nn/conv_s8.hpp"
#include "firmware/nn/encoder_arch.hpp"
#include "firmware/nn/encoder_model.hpp"
#include "firmware/nn/fully_connected_s8.hpp"
#include "firmware/nn/status.hpp"

namespace curio::nn {

// Arena layout: two ping-pong activation buffers (each layer reads one, writes the other)
// and the kernels' scratch. Layer i reads buffer i % 2 and writes buffer (i + 1) % 2; the
// image is copied into buffer 0.
namespace arena {

constexpr int32_t max2(int32_t a, int32_t b) {
  return a > b ? a : b;
}
constexpr int32_t round16(int32_t n) {
  return (n + 15) / 16 * 16;
}
// Bytes of the activation map entering conv layer i (i = 4: the flattened 4×4×32 map).
constexpr int32_t map_bytes(int32_t i) {
  return conv_map_size(i) * conv_map_size(i) * (i == 0 ? kImageChannels : kConvChannels);
}
constexpr Dims conv_input_dims(int32_t i) {
  return {1, conv_map_size(i), conv_map_size(i), conv_input_channels(i)};
}
constexpr Dims conv_filter_dims(int32_t i) {
  return {kConvChannels, kKernelSize, kKernelSize, conv_input_channels(i)};
}
// Stride and padding of every encoder conv (the rest of ConvParams is per layer).
inline constexpr ConvParams kConvParams{0, 0, {kConvStride, kConvStride}, {kConvPad, kConvPad}, {}};

// Buffer 0: the image, conv1's input, conv3's input (the flatten), fc2's output.
inline constexpr int32_t kPingBytes =
    round16(max2(max2(map_bytes(0), map_bytes(2)), max2(map_bytes(4), kHidden)));
// Buffer 1: conv0's output, conv2's output, fc1's output.
inline constexpr int32_t kPongBytes = round16(max2(max2(map_bytes(1), map_bytes(3)), kHidden));
inline constexpr int32_t kScratchBytes = round16(
    max2(max2(max2(conv_s8_get_buffer_size(kConvParams, conv_input_dims(0), conv_filter_dims(0)),
                   conv_s8_get_buffer_size(kConvParams, conv_input_dims(1), conv_filter_dims(1))),
              max2(conv_s8_get_buffer_size(kConvParams, conv_input_dims(2), conv_filter_dims(2)),
                   conv_s8_get_buffer_size(kConvParams, conv_input_dims(3), conv_filter_dims(3)))),
         max2(fully_connected_s8_get_buffer_size({1, kFlatten, kHidden}),
              fully_connected_s8_get_buffer_size({1, kHidden, kLatentOutputs}))));

// Prepared filters of the four convs (conv_s8_prepare: the host's channel-vector path), one
// after another; 0 bytes on Cortex-M.
constexpr int32_t prepared_offset(int32_t i) {
  return i == 0 ? 0 : prepared_offset(i - 1) + round16(conv_s8_prepared_bytes(conv_input_dims(i - 1), conv_filter_dims(i - 1)));
}
inline constexpr int32_t kPreparedBytes = prepared_offset(kConvLayers);

inline constexpr int32_t kPingOffset = 0;
inline constexpr int32_t kPongOffset = kPingBytes;
inline constexpr int32_t kScratchOffset = kPongOffset + kPongBytes;
inline constexpr int32_t kBytes = kScratchOffset + kScratchBytes;

static_assert(kPingBytes == 12288, "the 64·64·3 image is the largest even-layer map");
static_assert(kPongBytes == 32768, "conv0's 32·32·32 output is the largest odd-layer map");
// Cortex-M: 12 + 32 + 43.3 KiB, the scratch being conv1's row band (its filter widened to
// int16, 32 KiB; four widened input rows, 8.5 KiB; two window columns, 2 KiB; sums and
// requantization constants). Hosts: the channel-vector path's input copy.
static_assert(kScratchBytes <= (detail::kHostTarget ? 64 * 1024 : 44 * 1024),
              "kernel scratch: the row band or two im2col columns + sums (+ host SIMD path)");
static_assert(kBytes <= (detail::kHostTarget ? 112 : 90) * 1024, "RAM for all activations");
static_assert(kPingOffset % 16 == 0 && kPongOffset % 16 == 0 && kScratchOffset % 16 == 0,
              "every buffer starts 16-byte aligned");
static_assert(detail::kHostTarget || kPreparedBytes == 0, "Cortex-M: no prepared filters");

}  // namespace arena

// ReLU after a layer whose output zero point is output_offset, and the parameters of conv
// layer `layer` (stride, padding, offsets, ReLU): what Encoder runs, for tests and tools that
// run the same layers another way.
constexpr Activation relu_from(int32_t output_offset) {
  return {output_offset > -128 ? output_offset : -128, 127};
}
inline ConvParams conv_params_of(const QuantizedLayer& layer) {
  ConvParams p;
  p.input_offset = layer.input_offset;
  p.output_offset = layer.output_offset;
  p.stride = {kConvStride, kConvStride};
  p.padding = {kConvPad, kConvPad};
  p.activation = relu_from(layer.output_offset);
  return p;
}

class Encoder {
 public:
  // Keeps a copy of the model's pointers; the weight arrays they point at (flash) must
  // outlive the encoder.
  explicit Encoder(const EncoderModel& model) : model_(model) {}

  // μ of `image`; log_var may be nullptr. On failure (a kernel rejected its arguments,
  // i.e. a corrupt model) the outputs are untouched and faults() grows.
  Status encode(const uint8_t* image, float mu[kLatents], float log_var[kLatents] = nullptr);

  // `count` images one after another (each kImageBytes, contiguous): mu[i·kLatents + j],
  // log_var likewise (may be nullptr). Stops at the first failure; *done (optional) is then the
  // number of images encoded, each with the same outputs encode() gives it. Many images per
  // call for callers that hold them (curio-encode's folders; a controller that buffers
  // frames): the weights stay in cache between images and the filters are prepared once.
  Status encode_batch(const uint8_t* images, int32_t count, float* mu, float* log_var = nullptr,
                      int32_t* done = nullptr);

  uint32_t faults() const { return faults_; }
  uint32_t encodes() const { return encodes_; }

  // Profiling: `probe(user, layer)` is called in every encode after each layer finishes, layer
  // 0–3 the convs, 4 and 5 the hidden FCs, 6 the latent layer, and with layer −1 when the
  // image has been copied in (so the differences of a clock read there are the layers' costs;
  // tests/board/cycle_budget_main.cpp prints them). nullptr (the default) turns it off.
  using LayerProbe = void (*)(void* user, int32_t layer);
  // The output of `layer` (numbered as for the probe; 6: the latent layer's int32 sums) in the
  // arena: valid from the probe call for that layer until a later layer overwrites its
  // buffer. {nullptr, 0} for another number.
  struct LayerOutput {
    const void* data;
    int32_t bytes;
  };
  LayerOutput layer_output(int32_t layer) const;
  void set_layer_probe(LayerProbe probe, void* user) {
    probe_ = probe;
    probe_user_ = user;
  }

 private:
  Status run(const uint8_t* image, float mu[kLatents], float log_var[kLatents]);
  void probe(int32_t layer) const {
    if (probe_ != nullptr) probe_(probe_user_, layer);
  }

  EncoderModel model_;
  uint32_t faults_ = 0;
  uint32_t encodes_ = 0;
  LayerProbe probe_ = nullptr;
  void* probe_user_ = nullptr;
  // The convs' prepared filters, written at the first encode (they depend on the model only).
  bool filters_prepared_ = false;
  alignas(64) int8_t prepared_[arena::kPreparedBytes > 0 ? arena::kPreparedBytes : 1] = {};
  alignas(16) int8_t arena_[arena::kBytes] = {};
  int32_t latent_sums_[kLatentOutputs] = {};  // the last layer's int32 sums
};

}  // namespace curio::nn
