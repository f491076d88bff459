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

}  // namespace curio::nn::detail
