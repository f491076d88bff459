// requantize() over a row of int32 sums, written in 32-bit lanes (one widening multiply)
// so the compiler vectorizes it: the scalar form's 64-bit steps cost ~5× more per output
// and dominated the encoder's time. Bit-exact with fixed_point.hpp for multipliers ≥ 0
// (every rescale the quantizer emits; the kernels reject negative ones), because then
// the doubling high multiply can neither saturate nor needs gemmlowp's sign-dependent
// nudge: floor((a·b + 2^30) / 2^31) is the same value.
#pragma once
#include <cstdint>

#include "firmware/nn/fixed_point.hpp"

namespace curio::nn::detail {

inline int32_t requantize_lane(int32_t acc, int32_t bias, int32_t multiplier, int32_t shift,
                               int32_t output_offset, int32_t act_min, int32_t act_max) {
  // Saturating acc + bias without 64-bit arithmetic.
  const auto wrapped =
      static_cast<int32_t>(static_cast<uint32_t>(acc) + static_cast<uint32_t>(bias));
  const bool overflow = ((acc ^ wrapped) & (bias ^ wrapped)) < 0;
  const int32_t x = overflow ? (acc < 0 ? kInt32Min : kInt32Max) : wrapped;
  // Saturating left shift.
  const int32_t left = shift > 0 ? shift : 0;
  const int32_t right = shift > 0 ? 0 : -shift;
  const int32_t lo = kInt32Min >> left;
  const int32_t hi = kInt32Max >> left;
  const int32_t xl =
      x < lo ? kInt32Min
             : (x > hi ? kInt32Max : static_cast<int32_t>(static_cast<uint32_t>(x) << left));
  // Doubling high multiply, ties upward (multiplier ≥ 0).
  const int64_t product = static_cast<int64_t>(xl) * multiplier;
  const auto high = static_cast<int32_t>((product + (int64_t{1} << 30)) >> 31);
  // Rounding right shift, ties away from zero.
  const auto mask = static_cast<int32_t>((uint32_t{1} << right) - 1u);
  const int32_t remainder = high & mask;
  const int32_t threshold = (mask >> 1) + (high < 0 ? 1 : 0);
  const int32_t scaled = (high >> right) + (remainder > threshold ? 1 : 0);
  // + zero point (saturating, as requantize() does), clamp.
  const auto with_offset =
      static_cast<int32_t>(static_cast<uint32_t>(scaled) + static_cast<uint32_t>(output_offset));
  const bool offset_overflow = ((scaled ^ with_offset) & (output_offset ^ with_offset)) < 0;
  const int32_t v = offset_overflow ? (scaled < 0 ? kInt32Min : kInt32Max) : with_offset;
  return v < act_min ? act_min : (v > act_max ? act_max : v);
}

// The common case in fewer operations: every shift ≤ −1 (rescale < 0.5, so no left
// shift and no overflow adding the zero point) and acc + bias cannot overflow. Same
// integers as requantize_lane under those conditions.
inline int32_t requantize_lane_simple(int32_t acc_plus_bias, int32_t multiplier, int32_t right,
                                      int32_t output_offset, int32_t act_min, int32_t act_max) {
  const int64_t product = static_cast<int64_t>(acc_plus_bias) * multiplier;
  const auto high = static_cast<int32_t>((product + (int64_t{1} << 30)) >> 31);
  const auto mask = static_cast<int32_t>((uint32_t{1} << right) - 1u);
  const int32_t remainder = high & mask;
  const int32_t threshold = (mask >> 1) + (high < 0 ? 1 : 0);
  const int32_t v = (high >> right) + (remainder > threshold ? 1 : 0) + output_offset;
  return v < act_min ? act_min : (v > act_max ? act_max : v);
}

// Whether requantize_lane_simple applies to every channel, given that |acc| ≤ max_abs_acc.
inline bool requantize_is_simple(const int32_t* bias, const int32_t* shift, int32_t count,
                                 int32_t max_abs_acc) {
  for (int32_t i = 0; i < count; ++i) {
    if (shift[i] > -1) return false;
    if (bias != nullptr &&
        (bias[i] > kInt32Max - max_abs_acc || bias[i] < -(kInt32Max - max_abs_acc))) {
      return false;
    }
  }
  return true;
}

// out[i] = requantize(acc[i] + bias[i]) for i < count with per-channel rescales; bias may
// be nullptr. `simple` from requantize_is_simple() picks the shorter form. Each lane is
// narrowed as it is stored, in the same loop (a separate narrowing pass cost a tenth of the
// host encoder's time).
inline void requantize_row(const int32_t* acc, const int32_t* bias, const int32_t* multiplier,
                           const int32_t* shift, int32_t count, int32_t output_offset,
                           int32_t act_min, int32_t act_max, bool simple, int8_t* out) {
  if (simple) {
    if (bias != nullptr) {
      for (int32_t i = 0; i < count; ++i) {
        out[i] = static_cast<int8_t>(requantize_lane_simple(acc[i] + bias[i], multiplier[i], -shift[i],
                                                            output_offset, act_min, act_max));
      }
    } else {
      for (int32_t i = 0; i < count; ++i) {
        out[i] = static_cast<int8_t>(
            requantize_lane_simple(acc[i], multiplier[i], -shift[i], output_offset, act_min, act_max));
      }
    }
  } else if (bias != nullptr) {
    for (int32_t i = 0; i < count; ++i) {
      out[i] = static_cast<int8_t>(
          requantize_lane(acc[i], bias[i], multiplier[i], shift[i], output_offset, act_min, act_max));
    }
  } else {
    for (int32_t i = 0; i < count; ++i) {
      out[i] = static_cast<int8_t>(
          requantize_lane(acc[i], 0, multiplier[i], shift[i], output_offset, act_min, act_max));
    }
  }
}

}  // namespace curio::nn::detail
