// The inner loop every kernel runs: sums of products of int16 columns (input values with
// the input offset already added) with int8 filter rows, kCols × kRows at a time so each
// loaded value feeds several products. Written as plain loops over the depth for the
// compiler to vectorize; no intrinsics, so it builds unchanged for Cortex-M.
#pragma once
#include <cstdint>

namespace curio::nn::detail {

// acc[p·kRows + r] = Σ_k col[p·col_stride + k] · rows[r·row_stride + k], k < depth.
// Bounds: |col| ≤ 255, |row| ≤ 128, so depth < 65,000 cannot overflow int32.
template <int kCols, int kRows>
inline void dot_block(const int16_t* col, int32_t col_stride, const int8_t* rows,
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
