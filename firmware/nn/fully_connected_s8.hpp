// Fully connected layer, int8 in, per-output-channel requantization (CMSIS-NN's
// arm_fully_connected_s8 with per-channel weights). Filter [output_depth, input_depth]
// row-major (PyTorch's Linear layout).
#pragma once
#include <cstdint>

#include "firmware/nn/dot_block.hpp"
#include "firmware/nn/nn_types.hpp"
#include "firmware/nn/status.hpp"

namespace curio::nn {

// Scratch bytes both fully connected kernels need in ctx: one int16 input row, then one
// row of int32 sums.
constexpr int32_t fully_connected_s8_sums_offset(const FcDims& dims) {
  return detail::round_up(dims.input_depth * static_cast<int32_t>(sizeof(int16_t)), 16);
}
constexpr int32_t fully_connected_s8_get_buffer_size(const FcDims& dims) {
  return fully_connected_s8_sums_offset(dims) +
         detail::round_up(dims.output_depth * static_cast<int32_t>(sizeof(int32_t)), 16);
}

// output[b,o] = clamp(zp_out + rescale_o(bias[o] + Σ_i (input[b,i] + input_offset)·filter[o,i])).
Status fully_connected_s8(const Context& ctx, const FcParams& params,
                          const PerChannelQuantParams& quant, const FcDims& dims,
                          const int8_t* input, const int8_t* filter, const int32_t* bias,
                          int8_t* output);

// The same sum without rescaling: output[b,o] = bias[o] + Σ_i (input[b,i] + input_offset)·
// filter[o,i] as int32 (saturating), for a last layer dequantized by the caller
// (real = s_in·s_w[o]·output) so it keeps the accumulator's full precision.
Status fully_connected_s8_s32(const Context& ctx, int32_t input_offset, const FcDims& dims,
                              const int8_t* input, const int8_t* filter, const int32_t* bias,
                              int32_t* output);

// As fully_connected_s8_s32 with int16 weights in [−16383, 16383] (input_depth ≤ 514):
// for a small last layer whose weight rounding would otherwise dominate the output error.
Status fully_connected_s8_w16_s32(const Context& ctx, int32_t input_offset, const FcDims& dims,
                                  const int8_t* input, const int16_t* filter, const int32_t* bias,
                                  int32_t* output);

}  // namespace curio::nn
