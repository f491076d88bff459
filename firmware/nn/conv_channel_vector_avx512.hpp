// conv_s8's inner loop on AVX-512 VNNI hosts: 16 output channels per vector and one
// vpdpbusd per 4 window bytes read straight from the input (stored as u = x + 128 in a
// border of "zero point" bytes), so neither im2col nor horizontal sums. The unsigned
// input is corrected exactly: Σ (x + off)·w = Σ u·w + (off − 128)·Σ w. Only included when
// CURIO_NN_AVX512_VNNI; results are the same integers as the portable path.
#pragma once
#include <immintrin.h>

#include <cstdint>

namespace curio::nn::detail {

inline constexpr bool kChannelVectorUnsigned = true;  // the image holds x + 128

// Filter as 4-byte groups per channel: quads[(k/4)·c_out·4 + co·4 + (k & 3)], and the
// per-channel correction (input_offset − 128)·Σ_k w[co, k].
inline void prepare_weight_quads(const int8_t* filter, int32_t depth, int32_t c_out,
                                 int32_t input_offset, int8_t* quads, int32_t* correction) {
  for (int32_t co = 0; co < c_out; ++co) {
    int32_t sum = 0;
    for (int32_t k = 0; k < depth; ++k) sum += filter[co * depth + k];
    correction[co] = (input_offset - 128) * sum;
  }
  // Written in destination order, 4 bytes at a time (depth % 4 == 0).
  for (int32_t q = 0; q < depth / 4; ++q) {
    for (int32_t co = 0; co < c_out; ++co) {
      __builtin_memcpy(quads + (q * c_out + co) * 4, filter + co * depth + q * 4, 4);
    }
  }
}

// sums[p·c_out + co] = Σ_k x_p[k]·w[co, k] for kCols pixels, where pixel p's window row
// ky is the row_len bytes at pixel[p] + ky·row_stride (row_len % 4 == 0, so groups never
// straddle rows). c_out % 16 == 0.
template <int kCols>
inline void channel_vector_sums(const uint8_t* const* pixel, int32_t row_stride, int32_t rows,
                                int32_t row_len, const int8_t* quads, const int32_t* correction,
                                int32_t c_out, int32_t* sums) {
  for (int32_t co0 = 0; co0 < c_out; co0 += 16) {
    const __m512i start = _mm512_loadu_si512(correction + co0);
    __m512i acc[kCols];
    for (int p = 0; p < kCols; ++p) acc[p] = start;
    const int8_t* w = quads + co0 * 4;
    for (int32_t ky = 0; ky < rows; ++ky) {
      for (int32_t j = 0; j < row_len; j += 4, w += c_out * 4) {
        const __m512i wv = _mm512_loadu_si512(w);
        for (int p = 0; p < kCols; ++p) {
          int32_t x_quad;
          __builtin_memcpy(&x_quad, pixel[p] + ky * row_stride + j, sizeof x_quad);
          acc[p] = _mm512_dpbusd_epi32(acc[p], _mm512_set1_epi32(x_quad), wv);
        }
      }
    }
    for (int p = 0; p < kCols; ++p) _mm512_storeu_si512(sums + p * c_out + co0, acc[p]);
  }
}

}  // namespace curio::nn::detail
