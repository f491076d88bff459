// Integer arithmetic of int8 requantization (TFLite/CMSIS-NN semantics), shared by host and
// firmware. Semantics follow gemmlowp/TFLite so results match the industry's reference bit for bit,
// except that the left shift in multiply_by_quantized_multiplier saturates where TFLite's would
// overflow (undefined behaviour there).
#pragma once
#include <cstdint>
#include <limits>

namespace curio::nn {

inline constexpr int32_t kInt32Min = std::numeric_limits<int32_t>::min();
inline constexpr int32_t kInt32Max = std::numeric_limits<int32_t>::max();

constexpr int32_t saturate_to_int32(int64_t v) {
  return v < kInt32Min ? kInt32Min : (v > kInt32Max ? kInt32Max : static_cast<int32_t>(v));
}

constexpr int32_t saturating_add(int32_t a, int32_t b) {
  return saturate_to_int32(static_cast<int64_t>(a) + b);
}

constexpr int32_t saturating_sub(int32_t a, int32_t b) {
  return saturate_to_int32(static_cast<int64_t>(a) - b);
}

// a·b / 2^31 rounded to nearest, ties upward (gemmlowp's nudge: +0.5 → 1, −0.5 → 0);
// the one overflowing case INT32_MIN × INT32_MIN (= +1.0 in Q31) saturates to INT32_MAX.
constexpr int32_t saturating_rounding_doubling_high_mul(int32_t a, int32_t b) {
  if (a == kInt32Min && b == kInt32Min) return kInt32Max;
  const int64_t ab = static_cast<int64_t>(a) * b;
  const int64_t nudge = ab >= 0 ? (int64_t{1} << 30) : (1 - (int64_t{1} << 30));
  return static_cast<int32_t>((ab + nudge) / (int64_t{1} << 31));  // truncating division
}

// round(x / 2^exponent), ties away from zero, exponent in 0..31.
constexpr int32_t rounding_divide_by_pot(int32_t x, int exponent) {
  const auto mask = static_cast<int32_t>((int64_t{1} << exponent) - 1);
  const int32_t remainder = x & mask;
  const int32_t threshold = (mask >> 1) + (x < 0 ? 1 : 0);
  return (x >> exponent) + (remainder > threshold ? 1 : 0);
}

// x · multiplier / 2^31 · 2^shift with multiplier a Q31 value and shift in -31..30
// (positive: left). The left part saturates, the right part rounds ties away from zero.
constexpr int32_t multiply_by_quantized_multiplier(int32_t x, int32_t multiplier, int shift) {
  const int left = shift > 0 ? shift : 0;
  const int right = shift > 0 ? 0 : -shift;
  const int32_t shifted = saturate_to_int32(static_cast<int64_t>(x) * (int64_t{1} << left));
  return rounding_divide_by_pot(saturating_rounding_doubling_high_mul(shifted, multiplier), right);
}

// The last step of every int8 layer: rescale the int32 accumulator to the output scale,
// add the output zero point, clamp to the activation range (fused ReLU = [zp_out, 127]).
constexpr int8_t requantize(int32_t acc, int32_t multiplier, int shift, int32_t output_offset,
                            int32_t activation_min, int32_t activation_max) {
  int32_t v = multiply_by_quantized_multiplier(acc, multiplier, shift);
  v = saturating_add(v, output_offset);
  v = v < activation_min ? activation_min : v;
  v = v > activation_max ? activation_max : v;
  return static_cast<int8_t>(v);
}

}  // namespace curio::nn
