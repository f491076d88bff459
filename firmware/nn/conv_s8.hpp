// 2-D convolution, int8 in and out, per-output-channel requantization (CMSIS-NN's
// arm_convolve_s8): input NHWC, filter [C_out, H, W, C_in], int32 bias per output channel,
// padded inputs equal the input zero point (they contribute nothing).
#pragma once
#include <cstdint>

#include "nn/nn_types.hpp"
#include "nn/status.hpp"

namespace curio::nn {

// Scratch bytes conv_s8 needs in ctx (two int16 im2col columns).
constexpr int32_t conv_s8_get_buffer_size(const Dims& input_dims, const Dims& filter_dims) {
  return 2 * filter_dims.h * filter_dims.w * input_dims.c * static_cast<int32_t>(sizeof(int16_t));
}

// output[b,y,x,co] = clamp(zp_out + rescale_co(bias[co] + Σ (in + input_offset)·filter))
// where in runs over the filter window at (y·stride − pad, x·stride − pad). bias may be
// nullptr (zero). output_dims must be {n, (h + 2·pad − kh)/stride + 1, …, C_out}.
Status conv_s8(const Context& ctx, const ConvParams& params, const PerChannelQuantParams& quant,
               const Dims& input_dims, const int8_t* input, const Dims& filter_dims,
               const int8_t* filter, const int32_t* bias, const Dims& output_dims,
               int8_t* output);

}  // namespace curio::nn
