#include "firmware/nn/conv_s8.hpp"

#include "firmware/nn/dot_block.hpp"
#include "firmware/nn/fixed_point.hpp"
#include "firmware/nn/param_checks.hpp"
#include "firmware/nn/requantize_row.hpp"
#include "firmware/nn/simd.hpp"
#if CURIO_NN_AVX512_VNNI
#include "firmware/nn/conv_channel_vector_avx512.hpp"
#elif CURIO_NN_AVX2
#include "firmware/nn/conv_channel_vector_avx2.hpp"
#endif
#if CURIO_NN_ARM_DSP
#include "firmware/nn/dsp_ops.hpp"
#endif

namespace curio::nn {
namespace {

// The DSP path's columns hold each group of four values reordered (dsp_ops.hpp).
constexpr bool kReorderedColumns = CURIO_NN_ARM_DSP != 0;

void widen_row(const int8_t* src, int32_t count, int32_t offset, int16_t* dst) {
#if CURIO_NN_ARM_DSP
  detail::widen_with_offset_reordered(src, count, offset, dst);
#else
  detail::widen_with_offset(src, count, offset, dst);
#endif
}

// The filter window of output pixel (oy, ox) as one int16 column in filter order
// (ky, kx, c), input offset added; padded positions are 0 (= the zero point + offset),
// and so is the tail up to padded_depth. With kReorderedColumns each whole group of four
// is stored x0 x2 x1 x3: a window row that starts on a group (row length a multiple of 4)
// is widened straight into that order; otherwise the column is reordered at the end.
void im2col(const int8_t* image, const Dims& in, const Dims& f, const ConvParams& p, int32_t oy,
            int32_t ox, int32_t padded_depth, int16_t* col) {
  const int32_t row_len = f.w * in.c;
  const bool rows_on_groups = row_len % 4 == 0;
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
      if (kReorderedColumns && rows_on_groups) {
        widen_row(src_row + ix0 * in.c, row_len, p.input_offset, dst);
      } else {
        detail::widen_with_offset(src_row + ix0 * in.c, row_len, p.input_offset, dst);
      }
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
#if CURIO_NN_ARM_DSP
    if (rows_on_groups) detail::reorder_groups(dst, row_len);
#endif
  }
  for (int32_t i = f.h * row_len; i < padded_depth; ++i) col[i] = 0;
#if CURIO_NN_ARM_DSP
  if (!rows_on_groups) detail::reorder_groups(col, padded_depth);
#endif
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
  return detail::check_scratch(ctx, conv_s8_get_buffer_size(p, in, f));
}

// sums[p·c_out + co] = Σ col_p · filter row co for kCols columns (output pixels).
template <int kCols>
void pixel_sums(const int16_t* col, const int8_t* rows, int32_t depth, int32_t c_out,
                int32_t* sums) {
#if CURIO_NN_ARM_DSP
  if constexpr (kCols == 2) {
    detail::two_column_sums(col, rows, depth, c_out, sums);
    return;
  }
#endif
  int32_t co = 0;
  for (; co + 4 <= c_out; co += 4) {
    int32_t acc[kCols * 4];
#if CURIO_NN_ARM_DSP
    detail::dot_block_paired<kCols, 4>(col, depth, rows + co * depth, depth, depth, acc);
#else
    detail::dot_block<kCols, 4>(col, depth, rows + co * depth, depth, depth, acc);
#endif
    for (int p = 0; p < kCols; ++p) {
      for (int r = 0; r < 4; ++r) sums[p * c_out + co + r] = acc[p * 4 + r];
    }
  }
  for (; co < c_out; ++co) {
    int32_t acc[kCols];
#if CURIO_NN_ARM_DSP
    detail::dot_block_paired<kCols, 1>(col, depth, rows + co * depth, depth, depth, acc);
#else
    detail::dot_block<kCols, 1>(col, depth, rows + co * depth, depth, depth, acc);
#endif
    for (int p = 0; p < kCols; ++p) sums[p * c_out + co] = acc[p];
  }
}

}  // namespace

const char* simd_path() {
#if defined(CURIO_NN_EMULATE_DSP) && CURIO_NN_ARM_DSP
  return "arm-dsp-emulated";
#elif CURIO_NN_AVX2 && defined(__AVXVNNI__)
  return "avx2-vnni";
#elif CURIO_NN_AVX2
  return "avx2";
#else
  return CURIO_NN_AVX512_VNNI ? "avx512-vnni" : (CURIO_NN_ARM_DSP ? "arm-dsp" : "portable");
#endif
}

Status conv_s8_prepare(const ConvParams& params, const Dims& input_dims, const Dims& filter_dims,
                       const int8_t* filter, int8_t* prepared) {
  if (conv_s8_prepared_bytes(input_dims, filter_dims) == 0 || !CURIO_NN_CHANNEL_VECTOR) return Status::kOk;
  if (filter == nullptr || prepared == nullptr || !detail::valid_input_offset(params.input_offset))
    return Status::kArgumentError;
#if CURIO_NN_CHANNEL_VECTOR
  const int32_t depth = filter_dims.h * filter_dims.w * input_dims.c;
  detail::prepare_weight_quads(filter, depth, filter_dims.n, params.input_offset, prepared,
                               reinterpret_cast<int32_t*>(prepared + detail::round_up(filter_dims.n * depth, 16)));
#endif
  return Status::kOk;
}

Status conv_s8(const Context& ctx, const ConvParams& params, const PerChannelQuantParams& quant,
               const Dims& input_dims, const int8_t* input, const Dims& filter_dims,
               const int8_t* filter, const int32_t* bias, const Dims& output_dims, int8_t* output,
               [[maybe_unused]] const int8_t* prepared) {
  const Status status =
      check(ctx, params, quant, input_dims, input, filter_dims, filter, output_dims, output);
  if (status != Status::kOk) return status;

  const Dims& in = input_dims;
  const Dims& out = output_dims;
  const int32_t c_out = out.c;
  const ConvScratchLayout layout =
      conv_s8_scratch_layout(in, filter_dims, params.padding,
                             CURIO_NN_CHANNEL_VECTOR && conv_s8_channel_vector_shape(in, filter_dims));
  auto* const scratch = static_cast<int8_t*>(ctx.buf);
  int32_t* const sums = reinterpret_cast<int32_t*>(scratch + layout.sums_offset);
  int8_t* const filter_copy = scratch + layout.filter_offset;
  // |sum| ≤ depth · 255 · 128 (kMaxDepth keeps it below 2^31).
  const bool simple =
      detail::requantize_is_simple(bias, quant.shift, c_out, layout.depth * 255 * 128);
  auto requantize_pixels = [&](int8_t* dst, int32_t cols) {
#if CURIO_NN_ARM_DSP
    if (simple) {
      for (int32_t p = 0; p < cols; ++p) {
        detail::requantize_row_simple_s8(sums + p * c_out, bias, quant.multiplier, quant.shift, c_out,
                                         params.output_offset, params.activation.min,
                                         params.activation.max, dst + p * c_out);
      }
      return;
    }
#endif
    for (int32_t p = 0; p < cols; ++p) {
      detail::requantize_row(sums + p * c_out, bias, quant.multiplier, quant.shift, c_out,
                             params.output_offset, params.activation.min, params.activation.max,
                             simple, dst + p * c_out);
    }
  };

#if CURIO_NN_CHANNEL_VECTOR
  if (layout.channel_vector) {
    auto* const image_u8 = reinterpret_cast<uint8_t*>(scratch);
    const int32_t row_len = filter_dims.w * in.c;
    const int32_t row_stride = layout.image_w * in.c;
    const int8_t* quads = prepared;
    if (quads == nullptr) {
      detail::prepare_weight_quads(filter, layout.depth, c_out, params.input_offset, filter_copy,
                                   reinterpret_cast<int32_t*>(filter_copy + detail::round_up(c_out * layout.depth, 16)));
      quads = filter_copy;
    }
    const auto* const correction =
        reinterpret_cast<const int32_t*>(quads + detail::round_up(c_out * layout.depth, 16));
    // x + 128 (or x, kChannelVectorUnsigned false) for every input value; the border holds
    // the zero point (x + offset = 0).
    constexpr int32_t kStoredShift = detail::kChannelVectorUnsigned ? 128 : 0;
    const auto border = static_cast<uint8_t>(kStoredShift - params.input_offset);
    for (int32_t b = 0; b < in.n; ++b) {
      const int8_t* image = input + b * in.h * in.w * in.c;
      // Sizes in locals: byte stores may alias the Dims, which would reload them every byte.
      const int32_t image_bytes = layout.image_h * row_stride;
      const int32_t in_row = in.w * in.c;
      const int32_t pad_h = params.padding.h;
      const int32_t pad_row = params.padding.w * in.c;
      for (int32_t i = 0; i < image_bytes; ++i) image_u8[i] = border;
      for (int32_t y = 0; y < in.h; ++y) {
        const int8_t* src = image + y * in_row;
        uint8_t* dst = image_u8 + (y + pad_h) * row_stride + pad_row;
        for (int32_t i = 0; i < in_row; ++i) dst[i] = static_cast<uint8_t>(src[i] + kStoredShift);
      }
      for (int32_t oy = 0; oy < out.h; ++oy) {
        int8_t* out_row = output + ((b * out.h + oy) * out.w) * c_out;
        const uint8_t* window_row = image_u8 + oy * params.stride.h * row_stride;
        for (int32_t ox = 0; ox < out.w; ox += layout.cols) {
          const int32_t cols = out.w - ox < layout.cols ? out.w - ox : layout.cols;
          const uint8_t* pixel[8];
          for (int32_t p = 0; p < 8; ++p) {
            pixel[p] = window_row + (ox + (p < cols ? p : 0)) * params.stride.w * in.c;
          }
          if (cols == 8) {  // 8 independent sums hide vpdpbusd's latency
            detail::channel_vector_sums<8>(pixel, row_stride, filter_dims.h, row_len, quads,
                                           correction, c_out, sums);
          } else {  // a narrow map (conv3's is 4 wide): 4 pixels at a time, then single ones
            int32_t p = 0;
            for (; p + 4 <= cols; p += 4) {
              detail::channel_vector_sums<4>(pixel + p, row_stride, filter_dims.h, row_len, quads,
                                             correction, c_out, sums + p * c_out);
            }
            for (; p < cols; ++p) {
              detail::channel_vector_sums<1>(pixel + p, row_stride, filter_dims.h, row_len, quads,
                                             correction, c_out, sums + p * c_out);
            }
          }
          requantize_pixels(out_row + ox * c_out, cols);
        }
      }
    }
    return Status::kOk;
  }
#endif

  const int32_t depth = layout.col_depth;
  int16_t* const col = reinterpret_cast<int16_t*>(scratch);  // two columns, `depth` apart
  const int8_t* rows = filter;
  if (layout.filter_copied) {  // re-lay the filter with the padded stride
    for (int32_t co = 0; co < c_out; ++co) {
      for (int32_t k = 0; k < depth; ++k) {
        filter_copy[co * depth + k] = k < layout.depth ? filter[co * layout.depth + k] : int8_t{0};
      }
    }
    rows = filter_copy;
  }
  for (int32_t b = 0; b < in.n; ++b) {
    const int8_t* image = input + b * in.h * in.w * in.c;
    for (int32_t oy = 0; oy < out.h; ++oy) {
      int8_t* out_row = output + ((b * out.h + oy) * out.w) * c_out;
      int32_t ox = 0;
      for (; ox + 1 < out.w; ox += 2) {  // two output pixels share each filter load
        im2col(image, in, filter_dims, params, oy, ox, depth, col);
        im2col(image, in, filter_dims, params, oy, ox + 1, depth, col + depth);
        pixel_sums<2>(col, rows, depth, c_out, sums);
        requantize_pixels(out_row + ox * c_out, 2);
      }
      if (ox < out.w) {  // odd width: last pixel alone
        im2col(image, in, filter_dims, params, oy, ox, depth, col);
        pixel_sums<1>(col, rows, depth, c_out, sums);
        requantize_pixels(out_row + ox * c_out, 1);
      }
    }
  }
  return Status::kOk;
}

}  // namespace curio::nn
