#include "nn/conv_s8.hpp"

#include "nn/dot_block.hpp"
#include "nn/fixed_point.hpp"
#include "nn/param_checks.hpp"

namespace curio::nn {
namespace {

// The filter window of output pixel (oy, ox) as one int16 column in filter order
// (ky, kx, c), input offset added; padded positions are 0 (= the zero point + offset).
void im2col(const int8_t* image, const Dims& in, const Dims& f, const ConvParams& p, int32_t oy,
            int32_t ox, int16_t* col) {
  const int32_t row_len = f.w * in.c;
  const int32_t ix0 = ox * p.stride.w - p.padding.w;
  const bool row_inside = ix0 >= 0 && ix0 + f.w <= in.w;
  for (int32_t ky = 0; ky < f.h; ++ky) {
    const int32_t iy = oy * p.stride.h - p.padding.h + ky;
    int16_t* dst = col + ky * row_len;
    if (iy < 0 || iy >= in.h) {
      for (int32_t i = 0; i < row_len; ++i) dst[i] = 0;
      continue;
    }
    const int8_t* src_row = image + iy * in.w * in.c;
    if (row_inside) {  // the window's kx run is contiguous in NHWC
      detail::widen_with_offset(src_row + ix0 * in.c, row_len, p.input_offset, dst);
      continue;
    }
    for (int32_t kx = 0; kx < f.w; ++kx) {
      const int32_t ix = ix0 + kx;
      int16_t* d = dst + kx * in.c;
      if (ix < 0 || ix >= in.w) {
        for (int32_t c = 0; c < in.c; ++c) d[c] = 0;
      } else {
        detail::widen_with_offset(src_row + ix * in.c, in.c, p.input_offset, d);
      }
    }
  }
}

Status check(const Context& ctx, const ConvParams& p, const PerChannelQuantParams& q,
             const Dims& in, const int8_t* input, const Dims& f, const int8_t* filter,
             const Dims& out, const int8_t* output) {
  if (input == nullptr || filter == nullptr || output == nullptr) return Status::kArgumentError;
  if (in.n <= 0 || in.h <= 0 || in.w <= 0 || in.c <= 0 || f.n <= 0 || f.h <= 0 || f.w <= 0 ||
      p.stride.h <= 0 || p.stride.w <= 0 || p.padding.h < 0 || p.padding.w < 0) {
    return Status::kArgumentError;
  }
  if (f.c != in.c || out.c != f.n || out.n != in.n) return Status::kArgumentError;
  if (f.h * f.w > detail::kMaxDepth / in.c) return Status::kArgumentError;
  const int32_t span_h = in.h + 2 * p.padding.h - f.h;
  const int32_t span_w = in.w + 2 * p.padding.w - f.w;
  if (span_h < 0 || span_w < 0 || out.h != span_h / p.stride.h + 1 ||
      out.w != span_w / p.stride.w + 1) {
    return Status::kArgumentError;
  }
  if (!detail::valid_input_offset(p.input_offset) ||
      !detail::valid_output_offset(p.output_offset) || !detail::valid_activation(p.activation) ||
      !detail::valid_quant(q, f.n)) {
    return Status::kArgumentError;
  }
  return detail::check_scratch(ctx, conv_s8_get_buffer_size(in, f));
}

}  // namespace

Status conv_s8(const Context& ctx, const ConvParams& params, const PerChannelQuantParams& quant,
               const Dims& input_dims, const int8_t* input, const Dims& filter_dims,
               const int8_t* filter, const int32_t* bias, const Dims& output_dims,
               int8_t* output) {
  const Status status =
      check(ctx, params, quant, input_dims, input, filter_dims, filter, output_dims, output);
  if (status != Status::kOk) return status;

  const Dims& in = input_dims;
  const Dims& out = output_dims;
  const int32_t depth = filter_dims.h * filter_dims.w * in.c;
  const int32_t c_out = out.c;
  int16_t* const col = static_cast<int16_t*>(ctx.buf);  // two columns, `depth` apart

  auto store = [&](int8_t* dst, int32_t co, int32_t acc) {
    if (bias != nullptr) acc = saturating_add(acc, bias[co]);
    dst[co] = requantize(acc, quant.multiplier[co], quant.shift[co], params.output_offset,
                         params.activation.min, params.activation.max);
  };

  for (int32_t b = 0; b < in.n; ++b) {
    const int8_t* image = input + b * in.h * in.w * in.c;
    for (int32_t oy = 0; oy < out.h; ++oy) {
      int8_t* out_row = output + ((b * out.h + oy) * out.w) * c_out;
      int32_t ox = 0;
      for (; ox + 1 < out.w; ox += 2) {  // two output pixels share each filter load
        im2col(image, in, filter_dims, params, oy, ox, col);
        im2col(image, in, filter_dims, params, oy, ox + 1, col + depth);
        int8_t* dst0 = out_row + ox * c_out;
        int8_t* dst1 = dst0 + c_out;
        int32_t co = 0;
        for (; co + 4 <= c_out; co += 4) {
          int32_t acc[8];
          detail::dot_block<2, 4>(col, depth, filter + co * depth, depth, depth, acc);
          for (int32_t r = 0; r < 4; ++r) {
            store(dst0, co + r, acc[r]);
            store(dst1, co + r, acc[4 + r]);
          }
        }
        for (; co < c_out; ++co) {
          int32_t acc[2];
          detail::dot_block<2, 1>(col, depth, filter + co * depth, depth, depth, acc);
          store(dst0, co, acc[0]);
          store(dst1, co, acc[1]);
        }
      }
      if (ox < out.w) {  // odd width: last pixel alone
        im2col(image, in, filter_dims, params, oy, ox, col);
        int8_t* dst = out_row + ox * c_out;
        int32_t co = 0;
        for (; co + 4 <= c_out; co += 4) {
          int32_t acc[4];
          detail::dot_block<1, 4>(col, depth, filter + co * depth, depth, depth, acc);
          for (int32_t r = 0; r < 4; ++r) store(dst, co + r, acc[r]);
        }
        for (; co < c_out; ++co) {
          int32_t acc[1];
          detail::dot_block<1, 1>(col, depth, filter + co * depth, depth, depth, acc);
          store(dst, co, acc[0]);
        }
      }
    }
  }
  return Status::kOk;
}

}  // namespace curio::nn
