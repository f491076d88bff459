#include "firmware/nn/fully_connected_s8.hpp"

#include "firmware/nn/dot_block.hpp"
#include "firmware/nn/fixed_point.hpp"
#include "firmware/nn/param_checks.hpp"
#include "firmware/nn/requantize_row.hpp"
#include "firmware/nn/simd.hpp"
#if CURIO_NN_ARM_DSP
#include "firmware/nn/dsp_ops.hpp"
#endif

namespace curio::nn {
namespace {

Status check_common(const Context& ctx, int32_t input_offset, const FcDims& d, const int8_t* input,
                    const void* filter, const void* output) {
  if (input == nullptr || filter == nullptr || output == nullptr) return Status::kArgumentError;
  if (d.batches <= 0 || d.input_depth <= 0 || d.input_depth > detail::kMaxDepth ||
      d.output_depth <= 0) {
    return Status::kArgumentError;
  }
  if (!detail::valid_input_offset(input_offset)) return Status::kArgumentError;
  return detail::check_scratch(ctx, fully_connected_s8_get_buffer_size(d));
}

int32_t* sums_of(const Context& ctx, const FcDims& d) {
  return reinterpret_cast<int32_t*>(static_cast<int8_t*>(ctx.buf) +
                                    fully_connected_s8_sums_offset(d));
}

// sums[o] = Σ_i (input[i] + input_offset)·filter[o, i] for one batch row.
template <typename Weight>
void row_sums(const Context& ctx, int32_t input_offset, const FcDims& d, const int8_t* input,
              const Weight* filter, int32_t* sums) {
#if CURIO_NN_ARM_DSP
  if constexpr (sizeof(Weight) == 1) {  // int8 weights: paired MACs on a reordered column
    int16_t* const col = static_cast<int16_t*>(ctx.buf);
    const int32_t n = d.input_depth;
    detail::widen_with_offset_reordered(input, n, input_offset, col);
    int32_t o = 0;
    for (; o + 4 <= d.output_depth; o += 4) {
      detail::dot_block_paired<1, 4>(col, 0, filter + o * n, n, n, sums + o);
    }
    for (; o < d.output_depth; ++o) {
      detail::dot_block_paired<1, 1>(col, 0, filter + o * n, n, n, sums + o);
    }
    return;
  }
#endif
  int16_t* const col = static_cast<int16_t*>(ctx.buf);
  const int32_t n = d.input_depth;
  detail::widen_with_offset(input, n, input_offset, col);
  int32_t o = 0;
  for (; o + 4 <= d.output_depth; o += 4) {
    detail::dot_block<1, 4, Weight>(col, 0, filter + o * n, n, n, sums + o);
  }
  for (; o < d.output_depth; ++o) {
    detail::dot_block<1, 1, Weight>(col, 0, filter + o * n, n, n, sums + o);
  }
}

template <typename Weight>
void sums_plus_bias(const Context& ctx, int32_t input_offset, const FcDims& dims,
                    const int8_t* input, const Weight* filter, const int32_t* bias,
                    int32_t* output) {
  int32_t* const sums = sums_of(ctx, dims);
  for (int32_t b = 0; b < dims.batches; ++b) {
    row_sums(ctx, input_offset, dims, input + b * dims.input_depth, filter, sums);
    int32_t* dst = output + b * dims.output_depth;
    for (int32_t o = 0; o < dims.output_depth; ++o) {
      dst[o] = bias != nullptr ? saturating_add(sums[o], bias[o]) : sums[o];
    }
  }
}

}  // namespace

Status fully_connected_s8(const Context& ctx, const FcParams& params,
                          const PerChannelQuantParams& quant, const FcDims& dims,
                          const int8_t* input, const int8_t* filter, const int32_t* bias,
                          int8_t* output) {
  const Status status = check_common(ctx, params.input_offset, dims, input, filter, output);
  if (status != Status::kOk) return status;
  if (!detail::valid_output_offset(params.output_offset) ||
      !detail::valid_activation(params.activation) ||
      !detail::valid_quant(quant, dims.output_depth)) {
    return Status::kArgumentError;
  }
  int32_t* const sums = sums_of(ctx, dims);
  const bool simple = detail::requantize_is_simple(bias, quant.shift, dims.output_depth,
                                                   dims.input_depth * 255 * 128);
  for (int32_t b = 0; b < dims.batches; ++b) {
    row_sums(ctx, params.input_offset, dims, input + b * dims.input_depth, filter, sums);
#if CURIO_NN_ARM_DSP
    if (simple) {
      detail::requantize_row_simple_s8(sums, bias, quant.multiplier, quant.shift, dims.output_depth,
                                       params.output_offset, params.activation.min, params.activation.max,
                                       output + b * dims.output_depth);
      continue;
    }
#endif
    detail::requantize_row(sums, bias, quant.multiplier, quant.shift, dims.output_depth,
                           params.output_offset, params.activation.min, params.activation.max,
                           simple, output + b * dims.output_depth);
  }
  return Status::kOk;
}

Status fully_connected_s8_s32(const Context& ctx, int32_t input_offset, const FcDims& dims,
                              const int8_t* input, const int8_t* filter, const int32_t* bias,
                              int32_t* output) {
  const Status status = check_common(ctx, input_offset, dims, input, filter, output);
  if (status != Status::kOk) return status;
  sums_plus_bias(ctx, input_offset, dims, input, filter, bias, output);
  return Status::kOk;
}

Status fully_connected_s8_w16_s32(const Context& ctx, int32_t input_offset, const FcDims& dims,
                                  const int8_t* input, const int16_t* filter, const int32_t* bias,
                                  int32_t* output) {
  const Status status = check_common(ctx, input_offset, dims, input, filter, output);
  if (status != Status::kOk) return status;
  if (dims.input_depth > detail::kMaxDepthWide) return Status::kArgumentError;
  sums_plus_bias(ctx, input_offset, dims, input, filter, bias, output);
  return Status::kOk;
}

}  // namespace curio::nn
