#include "nn/fully_connected_s8.hpp"

#include "nn/dot_block.hpp"
#include "nn/fixed_point.hpp"
#include "nn/param_checks.hpp"

namespace curio::nn {
namespace {

Status check_common(const Context& ctx, int32_t input_offset, const FcDims& d,
                    const int8_t* input, const int8_t* filter, const void* output) {
  if (input == nullptr || filter == nullptr || output == nullptr) return Status::kArgumentError;
  if (d.batches <= 0 || d.input_depth <= 0 || d.input_depth > detail::kMaxDepth ||
      d.output_depth <= 0) {
    return Status::kArgumentError;
  }
  if (!detail::valid_input_offset(input_offset)) return Status::kArgumentError;
  return detail::check_scratch(ctx, fully_connected_s8_get_buffer_size(d));
}

// Runs `emit(batch, o, acc)` for every output with acc = Σ (input + offset)·filter[o].
template <typename Emit>
void accumulate(const Context& ctx, int32_t input_offset, const FcDims& d, const int8_t* input,
                const int8_t* filter, Emit emit) {
  int16_t* const col = static_cast<int16_t*>(ctx.buf);
  const int32_t n = d.input_depth;
  for (int32_t b = 0; b < d.batches; ++b) {
    detail::widen_with_offset(input + b * n, n, input_offset, col);
    int32_t o = 0;
    for (; o + 4 <= d.output_depth; o += 4) {
      int32_t acc[4];
      detail::dot_block<1, 4>(col, 0, filter + o * n, n, n, acc);
      for (int32_t r = 0; r < 4; ++r) emit(b, o + r, acc[r]);
    }
    for (; o < d.output_depth; ++o) {
      int32_t acc[1];
      detail::dot_block<1, 1>(col, 0, filter + o * n, n, n, acc);
      emit(b, o, acc[0]);
    }
  }
}

}  // namespace

Status fully_connected_s8(const Context& ctx, const FcParams& params,
                          const PerChannelQuantParams& quant, const FcDims& dims,
                          const int8_t* input, const int8_t* filter, const int32_t* bias,
                          int8_t* output) {
  Status status = check_common(ctx, params.input_offset, dims, input, filter, output);
  if (status != Status::kOk) return status;
  if (!detail::valid_output_offset(params.output_offset) ||
      !detail::valid_activation(params.activation) ||
      !detail::valid_quant(quant, dims.output_depth)) {
    return Status::kArgumentError;
  }
  accumulate(ctx, params.input_offset, dims, input, filter, [&](int32_t b, int32_t o, int32_t acc) {
    if (bias != nullptr) acc = saturating_add(acc, bias[o]);
    output[b * dims.output_depth + o] =
        requantize(acc, quant.multiplier[o], quant.shift[o], params.output_offset,
                   params.activation.min, params.activation.max);
  });
  return Status::kOk;
}

Status fully_connected_s8_s32(const Context& ctx, int32_t input_offset, const FcDims& dims,
                              const int8_t* input, const int8_t* filter, const int32_t* bias,
                              int32_t* output) {
  const Status status = check_common(ctx, input_offset, dims, input, filter, output);
  if (status != Status::kOk) return status;
  accumulate(ctx, input_offset, dims, input, filter, [&](int32_t b, int32_t o, int32_t acc) {
    output[b * dims.output_depth + o] = bias != nullptr ? saturating_add(acc, bias[o]) : acc;
  });
  return Status::kOk;
}

}  // namespace curio::nn
