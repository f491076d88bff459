// The inner loop every kernel runs: sums of products of int16 columns (input values with
// the input offset already added) with int8 filter rows, kCols × kRows at a time so each
// loaded value feeds several products. Written as plain loops over the depth for the
// compiler to vectorize; no intrinsics, so it builds unchanged for Cortex-M.
#pragma once
#include <cstdint>

namespace curio::nn::detail {

// Window lengths are padded (with zeros) to a multiple of this, so the compiler's vector
// loop covers a whole window: on wide-vector hosts an int8 vector holds 64 lanes and a
// 48-long window (4·4·3) would otherwise run entirely in the scalar tail (5× slower).
// Cortex-M's 32-bit SIMD needs only pairs.
#if defined(__ARM_ARCH)
inline constexpr int32_t kDepthGranule = 4;
inline constexpr bool kHostTarget = false;  // no host-only SIMD paths, no scratch for them
#else
inline constexpr int32_t kDepthGranule = 64;
inline constexpr bool kHostTarget = true;
#endif

constexpr int32_t round_up(int32_t n, int32_t to) {
  return (n + to - 1) / to * to;
}

// acc[p·kRows + r] = Σ_k col[p·col_stride + k] · rows[r·row_stride + k], k < depth.
// Bounds: |col| ≤ 255 and |row| ≤ 128 (int8) or ≤ 16383 (int16 weights), so a depth below
// 65,536 or 514 respectively cannot overflow int32.
template <int kCols, int kRows, typename Weight = int8_t>
inline void dot_block(const int16_t* col, int32_t col_stride, const Weight* rows,
                      int32_t row_stride, int32_t depth, int32_t* acc) {
  int32_t sum[kCols * kRows] = {};
  for (int32_t k = 0; k < depth; ++k) {
    for (int p = 0; p < kCols; ++p) {
      const int32_t x = col[p * col_stride + k];
      for (int r = 0; r < kRows; ++r) sum[p * kRows + r] += x * rows[r * row_stride + k];
    }
  }
  for (int i = 0; i < kCols * kRows; ++i) acc[i] = sum[i];
}

// dst[i] = src[i] + offset as int16 (the "q7 → q15 with offset" step of CMSIS-NN).
inline void widen_with_offset(const int8_t* src, int32_t count, int32_t offset, int16_t* dst) {
  for (int32_t i = 0; i < count; ++i) dst[i] = static_cast<int16_t>(src[i] + offset);
}

}  // namespace curio::nn::detail
