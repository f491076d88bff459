// The Cortex-M DSP instructions the paired-MAC path uses (CURIO_NN_ARM_DSP, simd.hpp), and the
// column layout they need. On a core with the DSP extension each is one instruction; elsewhere
// (CURIO_NN_EMULATE_DSP, host tests) the same operation in C, so the host checks the path's
// logic and the QEMU tests the instructions.
//
// The layout: SXTB16 sign-extends bytes 0 and 2 of a word into two int16 halves, and with
// ROR #8 bytes 1 and 3. A filter word (w0 w1 w2 w3) so gives the pairs (w0, w2) and (w1, w3)
// with no shuffle, and SMLAD multiplies each with a column word (x0, x2), (x1, x3): the
// columns hold each whole group of four values in the order x0 x2 x1 x3 ("reordered"). A
// group's partial sums are the same products added in another order, and no partial sum can
// overflow (dot_block.hpp's bounds), so the result equals the portable loop's bit for bit.
// The depth's last depth % 4 values (no whole group) stay in natural order.
#pragma once
#include <cstdint>
#include <cstring>

#if defined(__ARM_FEATURE_DSP) && !defined(CURIO_NN_EMULATE_DSP)
#include <arm_acle.h>
#endif

namespace curio::nn::detail {

inline uint32_t load_word(const void* p) {
  uint32_t w;
  std::memcpy(&w, p, sizeof w);  // one LDR (Cortex-M7 allows unaligned word loads)
  return w;
}
inline void store_word(void* p, uint32_t w) {
  std::memcpy(p, &w, sizeof w);
}

#if defined(__ARM_FEATURE_DSP) && !defined(CURIO_NN_EMULATE_DSP)

inline uint32_t sxtb16(uint32_t w) {
  return __sxtb16(w);
}
inline uint32_t sxtb16_ror8(uint32_t w) {
  uint32_t r;
  __asm__("sxtb16 %0, %1, ror #8" : "=r"(r) : "r"(w));  // GCC's ACLE has no rotate form
  return r;
}
inline uint32_t sadd16(uint32_t a, uint32_t b) {
  return __sadd16(a, b);
}
inline int32_t smlad(uint32_t x, uint32_t y, int32_t acc) {
  return __smlad(x, y, acc);
}
inline int32_t smmulr(int32_t a, int32_t b) {  // (a·b + 2^31) >> 32
  int32_t r;
  __asm__("smmulr %0, %1, %2" : "=r"(r) : "r"(a), "r"(b));
  return r;
}
inline uint32_t pkhbt_lsl16(uint32_t low, uint32_t high) {  // low's low half, high's low half on top
  uint32_t r;
  __asm__("pkhbt %0, %1, %2, lsl #16" : "=r"(r) : "r"(low), "r"(high));
  return r;
}
inline uint32_t pkhtb_asr16(uint32_t high, uint32_t low) {  // high's top half, low's top half below
  uint32_t r;
  __asm__("pkhtb %0, %1, %2, asr #16" : "=r"(r) : "r"(high), "r"(low));
  return r;
}

#else

inline uint32_t halves(int32_t lo, int32_t hi) {
  return (static_cast<uint32_t>(lo) & 0xFFFFu) | (static_cast<uint32_t>(hi) << 16);
}
inline int32_t low_half(uint32_t w) {
  return static_cast<int16_t>(w & 0xFFFFu);
}
inline int32_t high_half(uint32_t w) {
  return static_cast<int16_t>(w >> 16);
}
inline uint32_t sxtb16(uint32_t w) {
  return halves(static_cast<int8_t>(w & 0xFFu), static_cast<int8_t>((w >> 16) & 0xFFu));
}
inline uint32_t sxtb16_ror8(uint32_t w) {
  return sxtb16((w >> 8) | (w << 24));
}
inline uint32_t sadd16(uint32_t a, uint32_t b) {
  return halves(low_half(a) + low_half(b), high_half(a) + high_half(b));
}
inline int32_t smlad(uint32_t x, uint32_t y, int32_t acc) {
  const uint32_t s = static_cast<uint32_t>(low_half(x) * low_half(y)) +
                     static_cast<uint32_t>(high_half(x) * high_half(y)) + static_cast<uint32_t>(acc);
  return static_cast<int32_t>(s);  // wraps like the instruction (sums here never do)
}
inline int32_t smmulr(int32_t a, int32_t b) {
  return static_cast<int32_t>((static_cast<int64_t>(a) * b + (int64_t{1} << 31)) >> 32);
}
inline uint32_t pkhbt_lsl16(uint32_t low, uint32_t high) {
  return (low & 0xFFFFu) | (high << 16);
}
inline uint32_t pkhtb_asr16(uint32_t high, uint32_t low) {
  return (high & 0xFFFF0000u) | (low >> 16);
}

#endif

// dst = src + offset as int16, each whole group of four stored x0 x2 x1 x3 (two SXTB16 and two
// SADD16 per group), the last count % 4 in natural order.
inline void widen_with_offset_reordered(const int8_t* src, int32_t count, int32_t offset, int16_t* dst) {
  const uint32_t offsets = (static_cast<uint32_t>(offset) & 0xFFFFu) * 0x10001u;
  int32_t i = 0;
  for (; i + 4 <= count; i += 4) {
    const uint32_t w = load_word(src + i);
    store_word(dst + i, sadd16(sxtb16(w), offsets));
    store_word(dst + i + 2, sadd16(sxtb16_ror8(w), offsets));
  }
  for (; i < count; ++i) dst[i] = static_cast<int16_t>(src[i] + offset);
}

// A natural-order run of `count` values into the reordered layout (whole groups only).
inline void reorder_groups(int16_t* v, int32_t count) {
  for (int32_t i = 0; i + 4 <= count; i += 4) {
    const int16_t x1 = v[i + 1];
    v[i + 1] = v[i + 2];
    v[i + 2] = x1;
  }
}

// dot_block (dot_block.hpp) over reordered columns and natural int8 filter rows:
// acc[p·kRows + r] = Σ_k col_p[k] · rows_r[k], k < depth, 16 products per column and row
// group in 2 SMLAD.
template <int kCols, int kRows>
inline void dot_block_paired(const int16_t* col, int32_t col_stride, const int8_t* rows,
                             int32_t row_stride, int32_t depth, int32_t* acc) {
  int32_t sum[kCols * kRows] = {};
  const int32_t whole = depth & ~3;
  for (int32_t k = 0; k < whole; k += 4) {
    uint32_t x02[kCols];
    uint32_t x13[kCols];
    for (int p = 0; p < kCols; ++p) {
      x02[p] = load_word(col + p * col_stride + k);
      x13[p] = load_word(col + p * col_stride + k + 2);
    }
    for (int r = 0; r < kRows; ++r) {
      const uint32_t w = load_word(rows + r * row_stride + k);
      const uint32_t w02 = sxtb16(w);
      const uint32_t w13 = sxtb16_ror8(w);
      for (int p = 0; p < kCols; ++p) {
        sum[p * kRows + r] = smlad(x02[p], w02, sum[p * kRows + r]);
        sum[p * kRows + r] = smlad(x13[p], w13, sum[p * kRows + r]);
      }
    }
  }
  for (int32_t k = whole; k < depth; ++k) {
    for (int p = 0; p < kCols; ++p) {
      for (int r = 0; r < kRows; ++r) sum[p * kRows + r] += col[p * col_stride + k] * rows[r * row_stride + k];
    }
  }
  for (int i = 0; i < kCols * kRows; ++i) acc[i] = sum[i];
}

// The 2 × 2 block's sums over whole groups: s<column><row> += Σ col_c[k] · row_r[k] for
// `groups` groups of four, col1 and row1 at fixed offsets. Per group 2 LDRD, 2 LDR, 4 SXTB16
// and 8 SMLAD: 16 instructions for 16 products. On the DSP core the group is one asm block
// (GCC's own schedule spills and splits the LDRDs: 41 instructions for two groups), four per
// loop iteration; the emulated build runs the same steps in C.
struct Sums2x2 {
  int32_t s00, s01, s10, s11;  // s<column><row>
};

#if defined(__ARM_FEATURE_DSP) && !defined(CURIO_NN_EMULATE_DSP)
#define CURIO_NN_GROUP_2X2                                         \
  "ldrd %[a02], %[a13], [%[a]], #8\n\t"                             \
  "ldrd %[b02], %[b13], [%[b]], #8\n\t"                             \
  "ldr %[w], [%[r], %[d]]\n\t"                                      \
  "sxtb16 %[t], %[w]\n\t"                                           \
  "smlad %[s01], %[a02], %[t], %[s01]\n\t"                          \
  "smlad %[s11], %[b02], %[t], %[s11]\n\t"                          \
  "sxtb16 %[w], %[w], ror #8\n\t"                                   \
  "smlad %[s01], %[a13], %[w], %[s01]\n\t"                          \
  "smlad %[s11], %[b13], %[w], %[s11]\n\t"                          \
  "ldr %[w], [%[r]], #4\n\t"                                        \
  "sxtb16 %[t], %[w]\n\t"                                           \
  "smlad %[s00], %[a02], %[t], %[s00]\n\t"                          \
  "smlad %[s10], %[b02], %[t], %[s10]\n\t"                          \
  "sxtb16 %[w], %[w], ror #8\n\t"                                   \
  "smlad %[s00], %[a13], %[w], %[s00]\n\t"                          \
  "smlad %[s10], %[b13], %[w], %[s10]\n\t"

template <int kGroups>
inline void groups_2x2(const int16_t*& a, const int16_t*& b, const int8_t*& r, int32_t row_offset,
                       Sums2x2& s) {
  uint32_t a02, a13, b02, b13, w, t;
  if constexpr (kGroups == 4) {
    __asm__(CURIO_NN_GROUP_2X2 CURIO_NN_GROUP_2X2 CURIO_NN_GROUP_2X2 CURIO_NN_GROUP_2X2
            : [a] "+r"(a), [b] "+r"(b), [r] "+r"(r), [s00] "+r"(s.s00), [s01] "+r"(s.s01),
              [s10] "+r"(s.s10), [s11] "+r"(s.s11), [a02] "=&r"(a02), [a13] "=&r"(a13),
              [b02] "=&r"(b02), [b13] "=&r"(b13), [w] "=&r"(w), [t] "=&r"(t)
            : [d] "r"(row_offset)
            : "memory");
  } else {
    static_assert(kGroups == 1, "one group or four");
    __asm__(CURIO_NN_GROUP_2X2
            : [a] "+r"(a), [b] "+r"(b), [r] "+r"(r), [s00] "+r"(s.s00), [s01] "+r"(s.s01),
              [s10] "+r"(s.s10), [s11] "+r"(s.s11), [a02] "=&r"(a02), [a13] "=&r"(a13),
              [b02] "=&r"(b02), [b13] "=&r"(b13), [w] "=&r"(w), [t] "=&r"(t)
            : [d] "r"(row_offset)
            : "memory");
  }
}
#undef CURIO_NN_GROUP_2X2

#else

template <int kGroups>
inline void groups_2x2(const int16_t*& a, const int16_t*& b, const int8_t*& r, int32_t row_offset,
                       Sums2x2& s) {
  for (int g = 0; g < kGroups; ++g) {
    const uint32_t a02 = load_word(a), a13 = load_word(a + 2);
    const uint32_t b02 = load_word(b), b13 = load_word(b + 2);
    a += 4;
    b += 4;
    const uint32_t w1 = load_word(r + row_offset), w0 = load_word(r);
    r += 4;
    s.s01 = smlad(a13, sxtb16_ror8(w1), smlad(a02, sxtb16(w1), s.s01));
    s.s11 = smlad(b13, sxtb16_ror8(w1), smlad(b02, sxtb16(w1), s.s11));
    s.s00 = smlad(a13, sxtb16_ror8(w0), smlad(a02, sxtb16(w0), s.s00));
    s.s10 = smlad(b13, sxtb16_ror8(w0), smlad(b02, sxtb16(w0), s.s10));
  }
}

#endif

// sums[p·n_rows + r] = Σ_k col_p[k] · rows[r·depth + k] for two columns (col1 = col0 + depth,
// both 8-byte aligned) and every row, two rows at a time.
inline void two_column_sums(const int16_t* col0, const int8_t* rows, int32_t depth, int32_t n_rows,
                            int32_t* sums) {
  const int32_t groups = depth >> 2;
  const int32_t tail = depth & 3;
  int32_t r = 0;
  for (; r + 2 <= n_rows; r += 2) {
    Sums2x2 s{0, 0, 0, 0};
    const int16_t* a = col0;
    const int16_t* b = col0 + depth;
    const int8_t* w = rows + r * depth;
    int32_t g = groups;
    for (; g >= 4; g -= 4) groups_2x2<4>(a, b, w, depth, s);
    for (; g > 0; --g) groups_2x2<1>(a, b, w, depth, s);
    for (int32_t k = 0; k < tail; ++k) {
      s.s00 += a[k] * w[k];
      s.s01 += a[k] * w[depth + k];
      s.s10 += b[k] * w[k];
      s.s11 += b[k] * w[depth + k];
    }
    sums[r] = s.s00;
    sums[r + 1] = s.s01;
    sums[n_rows + r] = s.s10;
    sums[n_rows + r + 1] = s.s11;
  }
  if (r < n_rows) {
    int32_t acc[2];
    dot_block_paired<2, 1>(col0, depth, rows + r * depth, depth, depth, acc);
    sums[r] = acc[0];
    sums[n_rows + r] = acc[1];
  }
}

// The row-band conv path (conv_s8.cpp): the input rows a window reads, widened once each into
// int16 in natural order (x + offset), and the filter widened once per call, so the inner
// loop needs no SXTB16 at all: per group of four window values and 2 pixels × 2 filter rows,
// 4 LDRD and 8 SMLAD, 12 instructions for 16 products.

// dst = src + offset as int16 in natural order (x0 x1 x2 x3): SXTB16 twice, the halves
// packed back into order (PKHBT, PKHTB), SADD16 twice per group of four; the last count % 4
// one at a time.
inline void widen_with_offset_natural(const int8_t* src, int32_t count, int32_t offset, int16_t* dst) {
  const uint32_t offsets = (static_cast<uint32_t>(offset) & 0xFFFFu) * 0x10001u;
  int32_t i = 0;
  for (; i + 4 <= count; i += 4) {
    const uint32_t w = load_word(src + i);
    const uint32_t even = sxtb16(w);      // x0, x2
    const uint32_t odd = sxtb16_ror8(w);  // x1, x3
    store_word(dst + i, sadd16(pkhbt_lsl16(even, odd), offsets));
    store_word(dst + i + 2, sadd16(pkhtb_asr16(odd, even), offsets));
  }
  for (; i < count; ++i) dst[i] = static_cast<int16_t>(src[i] + offset);
}

// Copies `count` int16 values (count % 4 == 0, both pointers word-aligned) 8 bytes at a time
// and returns the end of dst: on the DSP core one LDRD and one STRD per four values.
inline int16_t* copy_groups(const int16_t* src, int32_t count, int16_t* dst) {
#if defined(__ARM_FEATURE_DSP) && !defined(CURIO_NN_EMULATE_DSP)
  for (int32_t i = 0; i < count; i += 4) {
    uint32_t lo, hi;
    // volatile: the store is its only effect that the compiler sees used
    __asm__ volatile("ldrd %[lo], %[hi], [%[s]], #8\n\t"
            "strd %[lo], %[hi], [%[d]], #8"
            : [s] "+r"(src), [d] "+r"(dst), [lo] "=&r"(lo), [hi] "=&r"(hi)
            :
            : "memory");
  }
  return dst;
#else
  std::memcpy(dst, src, static_cast<size_t>(count) * sizeof(int16_t));
  return dst + count;
#endif
}

// The 2 × 2 block over `kGroups` groups of four: a and b the two pixels' int16 window values,
// w the two filter rows' int16 values interleaved per group (row 0's four, then row 1's).
#if defined(__ARM_FEATURE_DSP) && !defined(CURIO_NN_EMULATE_DSP)
#define CURIO_NN_GROUP_WIDE_2X2                                    \
  "ldrd %[x0], %[x1], [%[a]], #8\n\t"                               \
  "ldrd %[y0], %[y1], [%[b]], #8\n\t"                               \
  "ldrd %[v0], %[v1], [%[w], #8]\n\t"                               \
  "smlad %[s01], %[x0], %[v0], %[s01]\n\t"                          \
  "smlad %[s01], %[x1], %[v1], %[s01]\n\t"                          \
  "smlad %[s11], %[y0], %[v0], %[s11]\n\t"                          \
  "smlad %[s11], %[y1], %[v1], %[s11]\n\t"                          \
  "ldrd %[v0], %[v1], [%[w]], #16\n\t"                              \
  "smlad %[s00], %[x0], %[v0], %[s00]\n\t"                          \
  "smlad %[s00], %[x1], %[v1], %[s00]\n\t"                          \
  "smlad %[s10], %[y0], %[v0], %[s10]\n\t"                          \
  "smlad %[s10], %[y1], %[v1], %[s10]\n\t"

template <int kGroups>
inline void wide_groups_2x2(const int16_t*& a, const int16_t*& b, const int16_t*& w, Sums2x2& s) {
  uint32_t x0, x1, y0, y1, v0, v1;
#define CURIO_NN_WIDE_OPERANDS                                                                     \
  : [a] "+r"(a), [b] "+r"(b), [w] "+r"(w), [s00] "+r"(s.s00), [s01] "+r"(s.s01), [s10] "+r"(s.s10), \
    [s11] "+r"(s.s11), [x0] "=&r"(x0), [x1] "=&r"(x1), [y0] "=&r"(y0), [y1] "=&r"(y1),              \
    [v0] "=&r"(v0), [v1] "=&r"(v1)                                                                 \
  :                                                                                                \
  : "memory"
  if constexpr (kGroups == 4) {
    __asm__(CURIO_NN_GROUP_WIDE_2X2 CURIO_NN_GROUP_WIDE_2X2 CURIO_NN_GROUP_WIDE_2X2
                CURIO_NN_GROUP_WIDE_2X2 CURIO_NN_WIDE_OPERANDS);
  } else if constexpr (kGroups == 3) {
    __asm__(CURIO_NN_GROUP_WIDE_2X2 CURIO_NN_GROUP_WIDE_2X2 CURIO_NN_GROUP_WIDE_2X2 CURIO_NN_WIDE_OPERANDS);
  } else {
    static_assert(kGroups == 1, "one, three or four groups");
    __asm__(CURIO_NN_GROUP_WIDE_2X2 CURIO_NN_WIDE_OPERANDS);
  }
#undef CURIO_NN_WIDE_OPERANDS
}
#undef CURIO_NN_GROUP_WIDE_2X2

#else

template <int kGroups>
inline void wide_groups_2x2(const int16_t*& a, const int16_t*& b, const int16_t*& w, Sums2x2& s) {
  for (int g = 0; g < kGroups; ++g) {
    const uint32_t x0 = load_word(a), x1 = load_word(a + 2);
    const uint32_t y0 = load_word(b), y1 = load_word(b + 2);
    const uint32_t v0 = load_word(w), v1 = load_word(w + 2);
    const uint32_t u0 = load_word(w + 4), u1 = load_word(w + 6);
    a += 4;
    b += 4;
    w += 8;
    s.s00 = smlad(x1, v1, smlad(x0, v0, s.s00));
    s.s10 = smlad(y1, v1, smlad(y0, v0, s.s10));
    s.s01 = smlad(x1, u1, smlad(x0, u0, s.s01));
    s.s11 = smlad(y1, u1, smlad(y0, u0, s.s11));
  }
}

#endif

// s += the 2 × 2 block's products over `groups` groups of four (pointers advance).
inline void wide_block_2x2(const int16_t* a, const int16_t* b, const int16_t* w, int32_t groups, Sums2x2& s) {
  for (; groups >= 4; groups -= 4) wide_groups_2x2<4>(a, b, w, s);
  if (groups == 3) {
    wide_groups_2x2<3>(a, b, w, s);
    return;
  }
  for (; groups > 0; --groups) wide_groups_2x2<1>(a, b, w, s);
}

// The row band's requantization, channel by channel over `cols` (1 or 2) pixels whose sums
// are c_out apart, with four constants per channel (band_requant_constants): 2·bias, the
// multiplier, 2^(right − 1) and right. The doubling high multiply is one SMMULR of the doubled
// sum: (2x·m + 2^31) >> 32 = (x·m + 2^30) >> 31, the same integer as requantize_lane_simple
// while |x| < 2^30 (band_requant_constants checks it), then the rounding right shift as in
// requantize_row_simple_s8.
inline void requantize_band_pixels(const int32_t* sums, const int32_t* constants, int32_t c_out, int32_t cols,
                                   int32_t output_offset, int32_t act_min, int32_t act_max, int8_t* out) {
  for (int32_t c = 0; c < c_out; ++c, constants += 4) {
    const int32_t bias2 = constants[0], multiplier = constants[1], round = constants[2], right = constants[3];
    for (int32_t p = 0; p < cols; ++p) {
      const int32_t high = smmulr(bias2 + 2 * sums[p * c_out + c], multiplier);
      int32_t v = ((high + round + (high >> 31)) >> right) + output_offset;
      v = v < act_min ? act_min : v;
      v = v > act_max ? act_max : v;
      out[p * c_out + c] = static_cast<int8_t>(v);
    }
  }
}

// requantize_row's simple form (requantize_row.hpp: every shift ≤ −1, acc + bias cannot
// overflow) writing int8 straight away, with the rounding right shift as one add and one
// shift: ties away from zero is floor((high + 2^(right−1) − [high < 0]) / 2^right), the same
// integer as requantize_lane_simple's remainder/threshold test (|high| ≤ 2^30 here, so the add
// cannot overflow). About 15 instructions an output instead of 35: conv0 requantizes 32
// outputs for every 48-long window.
inline void requantize_row_simple_s8(const int32_t* acc, const int32_t* bias, const int32_t* multiplier,
                                     const int32_t* shift, int32_t count, int32_t output_offset,
                                     int32_t act_min, int32_t act_max, int8_t* out) {
  for (int32_t i = 0; i < count; ++i) {
    const int32_t x = bias != nullptr ? acc[i] + bias[i] : acc[i];
    const int64_t product = static_cast<int64_t>(x) * multiplier[i] + (int64_t{1} << 30);
    const auto high = static_cast<int32_t>(product >> 31);
    const int32_t right = -shift[i];
    int32_t v = ((high + (int32_t{1} << (right - 1)) + (high >> 31)) >> right) + output_offset;
    v = v < act_min ? act_min : v;
    v = v > act_max ? act_max : v;
    out[i] = static_cast<int8_t>(v);
  }
}

}  // namespace curio::nn::detail
