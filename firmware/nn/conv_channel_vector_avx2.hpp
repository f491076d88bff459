// conv_s8's channel-vector loop on AVX2 hosts without AVX-512 (most laptops): the layout of
// conv_channel_vector_avx512.hpp (4-byte filter groups per channel, the window read straight
// from a bordered copy of the input) with 8 output channels per 256-bit vector.
//  - With AVX-VNNI (__AVXVNNI__: Alder Lake and later): one vpdpbusd per 4 window bytes, on
//    the input stored as u = x + 128, corrected by (off − 128)·Σ w as the AVX-512 path.
//  - AVX2 alone: vpmaddubsw needs an unsigned operand and saturates at int16, so the input
//    stays signed (x) and each product is |x|·(w·sign x): |x| ≤ 128 and |w| ≤ 127, so a
//    pair of products is at most 32,512 and never saturates; vpmaddwd then adds the pairs
//    into int32. Corrected by off·Σ w (Σ (x + off)·w = Σ x·w + off·Σ w).
// Only included when CURIO_NN_AVX2 (simd.hpp); the same integers as the portable path.
// c_out % 16 == 0 (conv_s8_channel_vector_shape).
#pragma once
#include <immintrin.h>

#include <cstdint>

namespace curio::nn::detail {

#if defined(__AVXVNNI__)
inline constexpr bool kChannelVectorUnsigned = true;  // the image holds x + 128
#else
inline constexpr bool kChannelVectorUnsigned = false;  // the image holds x
#endif

// Filter as 4-byte groups per channel: quads[(k/4)·c_out·4 + co·4 + (k & 3)], and the
// per-channel correction for how the image stores x.
inline void prepare_weight_quads(const int8_t* filter, int32_t depth, int32_t c_out,
                                 int32_t input_offset, int8_t* quads, int32_t* correction) {
  const int32_t stored_offset = kChannelVectorUnsigned ? input_offset - 128 : input_offset;
  for (int32_t co = 0; co < c_out; ++co) {
    int32_t sum = 0;
    for (int32_t k = 0; k < depth; ++k) sum += filter[co * depth + k];
    correction[co] = stored_offset * sum;
  }
  for (int32_t q = 0; q < depth / 4; ++q) {
    for (int32_t co = 0; co < c_out; ++co) {
      __builtin_memcpy(quads + (q * c_out + co) * 4, filter + co * depth + q * 4, 4);
    }
  }
}

// sums[p·c_out + co] = Σ_k x_p[k]·w[co, k] + correction[co] for kCols pixels, pixel p's
// window row ky being the row_len bytes at pixel[p] + ky·row_stride (row_len % 4 == 0).
// c_out % 16 == 0.
#if defined(__AVXVNNI__)

template <int kCols>
inline void channel_vector_sums(const uint8_t* const* pixel, int32_t row_stride, int32_t rows,
                                int32_t row_len, const int8_t* quads, const int32_t* correction,
                                int32_t c_out, int32_t* sums) {
  for (int32_t co0 = 0; co0 < c_out; co0 += 8) {
    const __m256i start = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(correction + co0));
    __m256i acc[kCols];
    for (int p = 0; p < kCols; ++p) acc[p] = start;
    const int8_t* w = quads + co0 * 4;
    for (int32_t ky = 0; ky < rows; ++ky) {
      for (int32_t j = 0; j < row_len; j += 4, w += c_out * 4) {
        const __m256i wv = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(w));
        for (int p = 0; p < kCols; ++p) {
          int32_t x_quad;
          __builtin_memcpy(&x_quad, pixel[p] + ky * row_stride + j, sizeof x_quad);
          acc[p] = _mm256_dpbusd_avx_epi32(acc[p], _mm256_set1_epi32(x_quad), wv);
        }
      }
    }
    for (int p = 0; p < kCols; ++p) {
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(sums + p * c_out + co0), acc[p]);
    }
  }
}

#else

// Up to 4 pixels × 16 channels (two vectors) at a time, so each pixel's |x| serves both
// channel vectors: per pixel and 4 window bytes, one broadcast and one abs, then per
// vector sign, vpmaddubsw, vpmaddwd and an add.
template <int kPixels>
inline void channel_vector_sums_16(const uint8_t* const* pixel, int32_t row_stride, int32_t rows,
                                   int32_t row_len, const int8_t* quads, const int32_t* correction,
                                   int32_t c_out, int32_t* sums) {
  const __m256i ones = _mm256_set1_epi16(1);
  for (int32_t co0 = 0; co0 < c_out; co0 += 16) {
    const __m256i start0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(correction + co0));
    const __m256i start1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(correction + co0 + 8));
    __m256i acc0[kPixels], acc1[kPixels];
    for (int p = 0; p < kPixels; ++p) {
      acc0[p] = start0;
      acc1[p] = start1;
    }
    const int8_t* w = quads + co0 * 4;
    for (int32_t ky = 0; ky < rows; ++ky) {
      for (int32_t j = 0; j < row_len; j += 4, w += c_out * 4) {
        const __m256i w0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(w));
        const __m256i w1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(w + 32));
        for (int p = 0; p < kPixels; ++p) {
          int32_t x_quad;
          __builtin_memcpy(&x_quad, pixel[p] + ky * row_stride + j, sizeof x_quad);
          const __m256i x = _mm256_set1_epi32(x_quad);
          const __m256i ax = _mm256_abs_epi8(x);
          const __m256i pairs0 = _mm256_maddubs_epi16(ax, _mm256_sign_epi8(w0, x));
          const __m256i pairs1 = _mm256_maddubs_epi16(ax, _mm256_sign_epi8(w1, x));
          acc0[p] = _mm256_add_epi32(acc0[p], _mm256_madd_epi16(pairs0, ones));
          acc1[p] = _mm256_add_epi32(acc1[p], _mm256_madd_epi16(pairs1, ones));
        }
      }
    }
    for (int p = 0; p < kPixels; ++p) {
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(sums + p * c_out + co0), acc0[p]);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(sums + p * c_out + co0 + 8), acc1[p]);
    }
  }
}

template <int kCols>
inline void channel_vector_sums(const uint8_t* const* pixel, int32_t row_stride, int32_t rows,
                                int32_t row_len, const int8_t* quads, const int32_t* correction,
                                int32_t c_out, int32_t* sums) {
  constexpr int kStep = kCols < 4 ? kCols : 4;
  static_assert(kCols % kStep == 0, "pixels in steps of 4 (or all of a smaller count)");
  for (int p = 0; p < kCols; p += kStep) {
    channel_vector_sums_16<kStep>(pixel + p, row_stride, rows, row_len, quads, correction, c_out,
                                  sums + p * c_out);
  }
}

#endif

}  // namespace curio::nn::detail
