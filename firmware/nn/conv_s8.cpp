#include "firmware/nn/conv_s8.hpp"

#include <cstring>

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

#if CURIO_NN_ARM_DSP
// The row band's filter: int16, rows r and r + 1 interleaved per group of four values (row
// r's four, then row r + 1's) in a block of 2·depth at r·depth; an odd last row in natural
// order. depth % 4 == 0.
void widen_filter_pairs(const int8_t* filter, int32_t depth, int32_t c_out, int16_t* dst) {
  int32_t r = 0;
  for (; r + 2 <= c_out; r += 2) {
    const int8_t* w0 = filter + r * depth;
    int16_t* d = dst + r * depth;
    for (int32_t k = 0; k < depth; k += 4, d += 8) {
      detail::widen_with_offset_natural(w0 + k, 4, 0, d);
      detail::widen_with_offset_natural(w0 + depth + k, 4, 0, d + 4);
    }
  }
  if (r < c_out) detail::widen_with_offset_natural(filter + r * depth, depth, 0, dst + r * depth);
}

// One input row into its slot: `pad` zeros, the row's values + offset, zeros to slot_values.
void widen_band_row(const int8_t* src, int32_t count, int32_t pad, int32_t slot_values, int32_t offset,
                    int16_t* dst) {
  for (int32_t i = 0; i < pad; ++i) dst[i] = 0;
  detail::widen_with_offset_natural(src, count, offset, dst + pad);
  for (int32_t i = pad + count; i < slot_values; ++i) dst[i] = 0;
}

// Two pixels' sums over every filter row: pixel 0's window row i at window_row[i] + x, pixel
// 1's `step` further, copied one after another into two contiguous columns (the 2 × 2 block
// then runs over the whole window at once); w_first the first used window row in row pair
// 0's block.
void band_sums_2x2(const int16_t* const* window_row, int32_t rows, int32_t x, int32_t step, int32_t row_len,
                   const int16_t* w_first, const int8_t* filter, int32_t ky_offset, int32_t depth, int32_t c_out,
                   int16_t* cols, int32_t* sums) {
  const int32_t used = rows * row_len;
  int16_t* const col0 = cols;
  int16_t* const col1 = cols + used;
  int16_t* d0 = col0;
  int16_t* d1 = col1;
  for (int32_t i = 0; i < rows; ++i) {  // row_len % 4 == 0; windows and columns word-aligned
    const int16_t* a = window_row[i] + x;
    d0 = detail::copy_groups(a, row_len, d0);
    d1 = detail::copy_groups(a + step, row_len, d1);
  }
  const int32_t groups = used / 4;
  int32_t r = 0;
  for (; r + 2 <= c_out; r += 2) {
    detail::Sums2x2 s{0, 0, 0, 0};
    detail::wide_block_2x2(col0, col1, w_first + r * depth, groups, s);
    sums[r] = s.s00;
    sums[r + 1] = s.s01;
    sums[c_out + r] = s.s10;
    sums[c_out + r + 1] = s.s11;
  }
  for (; r < c_out; ++r) {  // an odd last row, from the int8 filter
    int32_t s0 = 0, s1 = 0;
    const int8_t* w = filter + r * depth + ky_offset;
    for (int32_t k = 0; k < used; ++k) {
      s0 += col0[k] * w[k];
      s1 += col1[k] * w[k];
    }
    sums[r] = s0;
    sums[c_out + r] = s1;
  }
}

// The row band's requantization constants (detail::requantize_band_pixels) for every channel;
// false where they do not apply: a shift above −1, or a sum + bias that could reach 2^30.
bool band_requant_constants(const int32_t* bias, const PerChannelQuantParams& q, int32_t c_out,
                            int32_t max_abs_acc, int32_t* constants) {
  for (int32_t c = 0; c < c_out; ++c, constants += 4) {
    const int32_t b = bias != nullptr ? bias[c] : 0;
    const int32_t right = -q.shift[c];
    if (right < 1 || right > 31 || b > (int32_t{1} << 30) - 1 - max_abs_acc ||
        b < -((int32_t{1} << 30) - 1 - max_abs_acc)) {
      return false;
    }
    constants[0] = 2 * b;
    constants[1] = q.multiplier[c];
    constants[2] = static_cast<int32_t>(uint32_t{1} << (right - 1));
    constants[3] = right;
  }
  return true;
}

// One pixel's sums (an odd last pixel of a row), from the int8 filter.
void band_sums_1(const int16_t* const* window_row, int32_t rows, int32_t x, int32_t row_len, int32_t ky_offset,
                 const int8_t* filter, int32_t depth, int32_t c_out, int32_t* sums) {
  for (int32_t r = 0; r < c_out; ++r) {
    int32_t s = 0;
    const int8_t* w = filter + r * depth + ky_offset;
    for (int32_t i = 0; i < rows; ++i, w += row_len) {
      const int16_t* a = window_row[i] + x;
      for (int32_t j = 0; j < row_len; ++j) s += a[j] * w[j];
    }
    sums[r] = s;
  }
}
#endif

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
  // Each of `cols` pixels' c_out sums at from + p·c_out → int8 at dst + p·c_out.
  auto requantize_from = [&](const int32_t* from, int8_t* dst, int32_t cols) {
#if CURIO_NN_AVX512_VNNI
    if (simple && c_out % 16 == 0) {
      detail::requantize_pixels_simple(from, bias, quant.multiplier, quant.shift, c_out, cols, params.output_offset,
                                       params.activation.min, params.activation.max, dst);
      return;
    }
#endif
#if CURIO_NN_ARM_DSP
    if (simple) {
      for (int32_t p = 0; p < cols; ++p) {
        detail::requantize_row_simple_s8(from + p * c_out, bias, quant.multiplier, quant.shift, c_out,
                                         params.output_offset, params.activation.min,
                                         params.activation.max, dst + p * c_out);
      }
      return;
    }
#endif
    for (int32_t p = 0; p < cols; ++p) {
      detail::requantize_row(from + p * c_out, bias, quant.multiplier, quant.shift, c_out,
                             params.output_offset, params.activation.min, params.activation.max,
                             simple, dst + p * c_out);
    }
  };
  auto requantize_pixels = [&](int8_t* dst, int32_t cols) { requantize_from(sums, dst, cols); };

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
#if CURIO_NN_AVX512_VNNI
          const int32_t step = params.stride.w * in.c;
          int8_t* const out_pixels = out_row + ox * c_out;
          if (simple && cols == 8 && c_out % 32 == 0 && (step == 6 || step == 64)) {  // requantized in registers
            const detail::RequantizeOutput o =
                detail::requantize_output(params.output_offset, params.activation.min, params.activation.max);
            if (step == 6) {
              detail::channel_vector_conv_strided<8, 6>(pixel[0], row_stride, filter_dims.h, row_len, quads, correction,
                                                        c_out, bias, quant.multiplier, quant.shift, o, out_pixels);
            } else {
              detail::channel_vector_conv_strided<8, 64>(pixel[0], row_stride, filter_dims.h, row_len, quads,
                                                         correction, c_out, bias, quant.multiplier, quant.shift, o,
                                                         out_pixels);
            }
            continue;
          }
          if (cols == 8 && c_out % 32 == 0 && (step == 6 || step == 64)) {  // the encoder's convs: conv0, conv1–3
            if (step == 6) {
              detail::channel_vector_sums_strided<8, 6>(pixel[0], row_stride, filter_dims.h, row_len, quads,
                                                        correction, c_out, sums);
            } else {
              detail::channel_vector_sums_strided<8, 64>(pixel[0], row_stride, filter_dims.h, row_len, quads,
                                                         correction, c_out, sums);
            }
          } else
#endif
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

#if CURIO_NN_ARM_DSP
  const ConvBandLayout band = conv_s8_band_layout(in, filter_dims, params);
  if (band.usable) {
    auto* const wide_filter = reinterpret_cast<int16_t*>(scratch);
    auto* const ring = reinterpret_cast<int16_t*>(scratch + band.ring_offset);
    auto* const band_sums = reinterpret_cast<int32_t*>(scratch + band.sums_offset);
    const int32_t depth = layout.depth;
    widen_filter_pairs(filter, depth, c_out, wide_filter);
    const int32_t row_len = filter_dims.w * in.c;
    const int32_t kh = filter_dims.h;
    const int32_t slot_values = band.slot_values;
    auto* const cols = reinterpret_cast<int16_t*>(scratch + band.cols_offset);
    auto* const constants = reinterpret_cast<int32_t*>(scratch + band.requant_offset);
    const bool fast_requant = layout.depth <= (int32_t{1} << 30) / (255 * 128) &&
                              band_requant_constants(bias, quant, c_out, layout.depth * 255 * 128, constants);
    auto requantize_band = [&](int8_t* dst, int32_t n) {
      if (fast_requant) {
        detail::requantize_band_pixels(band_sums, constants, c_out, n, params.output_offset,
                                       params.activation.min, params.activation.max, dst);
      } else {
        requantize_from(band_sums, dst, n);
      }
    };
    const int32_t pixel_step = params.stride.w * in.c;  // int16 values between two windows
    for (int32_t b = 0; b < in.n; ++b) {
      const int8_t* image = input + b * in.h * in.w * in.c;
      int32_t slot_row[kBandMaxRows];
      for (int32_t k = 0; k < kh; ++k) slot_row[k] = -1;  // holds no row yet
      for (int32_t oy = 0; oy < out.h; ++oy) {
        // The rows this output row reads, each widened once into slot (iy + pad) mod kh;
        // rows outside the image are zeros and add nothing, so they are skipped.
        const int16_t* window_row[kBandMaxRows];
        int32_t rows = 0;
        int32_t first_ky = 0;
        for (int32_t ky = 0; ky < kh; ++ky) {
          const int32_t iy = oy * params.stride.h - params.padding.h + ky;
          if (iy < 0 || iy >= in.h) {
            if (rows == 0) first_ky = ky + 1;
            continue;
          }
          const int32_t slot = (iy + params.padding.h) % kh;
          int16_t* dst = ring + slot * slot_values;
          if (slot_row[slot] != iy) {
            widen_band_row(image + iy * in.w * in.c, in.w * in.c, params.padding.w * in.c, slot_values,
                           params.input_offset, dst);
            slot_row[slot] = iy;
          }
          window_row[rows++] = dst;
        }
        const int16_t* const w_first = wide_filter + first_ky * row_len * 2;
        int8_t* out_row = output + ((b * out.h + oy) * out.w) * c_out;
        int32_t ox = 0;
        for (; ox + 1 < out.w; ox += 2) {
          band_sums_2x2(window_row, rows, ox * pixel_step, pixel_step, row_len, w_first, filter,
                        first_ky * row_len, depth, c_out, cols, band_sums);
          requantize_band(out_row + ox * c_out, 2);
        }
        if (ox < out.w) {
          band_sums_1(window_row, rows, ox * pixel_step, row_len, first_ky * row_len, filter, depth, c_out,
                      band_sums);
          requantize_band(out_row + ox * c_out, 1);
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
