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

// The sums of output channels co0 .. co0+31 for kCols pixels kStep bytes apart: the
// correction, then every input quad broadcast into two vpdpbusd (channels co0..+15 in acc0,
// co0+16..+31 in acc1). Shared by the kernels below; inlined, the accumulators stay in
// registers.
template <int kCols, int kStep>
__attribute__((always_inline)) inline void channel_block_sums(
    const uint8_t* base, int32_t row_stride, int32_t rows, int32_t row_len, const int8_t* quads,
    const int32_t* correction, int32_t c_out, int32_t co0, __m512i (&acc0)[kCols],
    __m512i (&acc1)[kCols]) {
  const __m512i start0 = _mm512_loadu_si512(correction + co0);
  const __m512i start1 = _mm512_loadu_si512(correction + co0 + 16);
  for (int p = 0; p < kCols; ++p) {
    acc0[p] = start0;
    acc1[p] = start1;
  }
  const int8_t* w = quads + co0 * 4;
  for (int32_t ky = 0; ky < rows; ++ky) {
    const uint8_t* x = base + ky * row_stride;
    for (int32_t j = 0; j < row_len; j += 4, w += c_out * 4, x += 4) {
      const __m512i w0 = _mm512_loadu_si512(w);
      const __m512i w1 = _mm512_loadu_si512(w + 64);
      for (int p = 0; p < kCols; ++p) {
        int32_t x_quad;
        __builtin_memcpy(&x_quad, x + p * kStep, sizeof x_quad);
        const __m512i xv = _mm512_set1_epi32(x_quad);
        acc0[p] = _mm512_dpbusd_epi32(acc0[p], xv, w0);
        acc1[p] = _mm512_dpbusd_epi32(acc1[p], xv, w1);
      }
    }
  }
}

// channel_vector_sums for kCols pixels kStep bytes apart from `base` (kStep a compile-time
// constant: one pointer advances and each pixel is a fixed displacement from it, where the
// general form advances a pointer per pixel: 8 more instructions per 8 vpdpbusd), 32 channels
// at a time (c_out % 32 == 0): each broadcast input quad feeds two vpdpbusd, so broadcasts,
// which compete with vpdpbusd for the vector ports, are half as many (16 accumulators, two
// weight vectors and the broadcast stay in registers).
template <int kCols, int kStep>
inline void channel_vector_sums_strided(const uint8_t* base, int32_t row_stride, int32_t rows,
                                        int32_t row_len, const int8_t* quads,
                                        const int32_t* correction, int32_t c_out, int32_t* sums) {
  for (int32_t co0 = 0; co0 < c_out; co0 += 32) {
    __m512i acc0[kCols], acc1[kCols];
    channel_block_sums<kCols, kStep>(base, row_stride, rows, row_len, quads, correction, c_out,
                                     co0, acc0, acc1);
    for (int p = 0; p < kCols; ++p) {
      _mm512_storeu_si512(sums + p * c_out + co0, acc0[p]);
      _mm512_storeu_si512(sums + p * c_out + co0 + 16, acc1[p]);
    }
  }
}

// requantize_row's simple form (every shift ≤ −1, acc + bias cannot overflow), 16 channels a
// vector: the doubling high multiply exact in 64-bit lanes (vpmuldq on the even and the odd
// channels), the rounding right shift as (high + 2^(right−1) + [high < 0 ? −1 : 0]) >> right,
// the same integers as requantize_lane_simple. The scalar-per-lane loop the compiler made of
// requantize_row was half of conv0's time.
// (GCC 12 warns that the shift intrinsics' internal _mm512_undefined_epi32 may be uninitialized.)
// Clang has no such warning group (and -Werror would refuse the unknown name), so GCC only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
struct RequantizeVector {  // one block of 16 channels' constants
  __m512i bias, multiplier, multiplier_odd, right, round;
};
struct RequantizeOutput {  // what every channel shares
  __m512i round30, offset, lo, hi;
};
inline RequantizeOutput requantize_output(int32_t output_offset, int32_t act_min, int32_t act_max) {
  return {_mm512_set1_epi64(int64_t{1} << 30), _mm512_set1_epi32(output_offset),
          _mm512_set1_epi32(act_min), _mm512_set1_epi32(act_max)};
}
inline RequantizeVector requantize_constants(const int32_t* bias, const int32_t* multiplier,
                                             const int32_t* shift) {
  const __m512i one = _mm512_set1_epi32(1);
  RequantizeVector k;
  k.bias = bias != nullptr ? _mm512_loadu_si512(bias) : _mm512_setzero_si512();
  k.multiplier = _mm512_loadu_si512(multiplier);
  k.multiplier_odd = _mm512_srli_epi64(k.multiplier, 32);
  k.right = _mm512_sub_epi32(_mm512_setzero_si512(), _mm512_loadu_si512(shift));
  k.round = _mm512_sllv_epi32(one, _mm512_sub_epi32(k.right, one));
  return k;
}
inline __m128i requantize16(__m512i acc, const RequantizeVector& k, const RequantizeOutput& o) {
  const __m512i x = _mm512_add_epi32(acc, k.bias);
  const __m512i even =
      _mm512_srai_epi64(_mm512_add_epi64(_mm512_mul_epi32(x, k.multiplier), o.round30), 31);
  const __m512i odd = _mm512_srai_epi64(
      _mm512_add_epi64(_mm512_mul_epi32(_mm512_srli_epi64(x, 32), k.multiplier_odd), o.round30),
      31);
  const __m512i high = _mm512_mask_blend_epi32(0xAAAA, even, _mm512_slli_epi64(odd, 32));
  const __m512i nudged =
      _mm512_add_epi32(_mm512_add_epi32(high, k.round), _mm512_srai_epi32(high, 31));
  const __m512i v = _mm512_add_epi32(_mm512_srav_epi32(nudged, k.right), o.offset);
  return _mm512_cvtsepi32_epi8(_mm512_min_epi32(_mm512_max_epi32(v, o.lo), o.hi));
}

// `cols` pixels of c_out sums each (c_out % 16 == 0) → int8; the constants loaded once per 16
// channels for all pixels.
inline void requantize_pixels_simple(const int32_t* sums, const int32_t* bias,
                                     const int32_t* multiplier, const int32_t* shift, int32_t c_out,
                                     int32_t cols, int32_t output_offset, int32_t act_min,
                                     int32_t act_max, int8_t* out) {
  const RequantizeOutput o = requantize_output(output_offset, act_min, act_max);
  for (int32_t c = 0; c < c_out; c += 16) {
    const RequantizeVector k =
        requantize_constants(bias != nullptr ? bias + c : nullptr, multiplier + c, shift + c);
    for (int32_t p = 0; p < cols; ++p) {
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + p * c_out + c),
                       requantize16(_mm512_loadu_si512(sums + p * c_out + c), k, o));
    }
  }
}

// channel_vector_sums_strided with the requantization done on the accumulators (the simple
// form's conditions hold): int8 straight to out (pixel p at out + p·c_out), no int32 sums
// stored and loaded again.
template <int kCols, int kStep>
inline void channel_vector_conv_strided(const uint8_t* base, int32_t row_stride, int32_t rows,
                                        int32_t row_len, const int8_t* quads,
                                        const int32_t* correction, int32_t c_out,
                                        const int32_t* bias, const int32_t* multiplier,
                                        const int32_t* shift, const RequantizeOutput& o,
                                        int8_t* out) {
  for (int32_t co0 = 0; co0 < c_out; co0 += 32) {
    __m512i acc0[kCols], acc1[kCols];
    channel_block_sums<kCols, kStep>(base, row_stride, rows, row_len, quads, correction, c_out,
                                     co0, acc0, acc1);
    const RequantizeVector k0 =
        requantize_constants(bias != nullptr ? bias + co0 : nullptr, multiplier + co0, shift + co0);
    for (int p = 0; p < kCols; ++p) {
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + p * c_out + co0),
                       requantize16(acc0[p], k0, o));
    }
    const RequantizeVector k1 = requantize_constants(bias != nullptr ? bias + co0 + 16 : nullptr,
                                                     multiplier + co0 + 16, shift + co0 + 16);
    for (int p = 0; p < kCols; ++p) {
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + p * c_out + co0 + 16),
                       requantize16(acc1[p], k1, o));
    }
  }
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

}  // namespace curio::nn::detail
