// Fixed-point helpers at their edges, and against the definitions in reference_kernels.hpp.
#include "firmware/nn/fixed_point.hpp"
#include "firmware/nn/requantize_row.hpp"

#include <gtest/gtest.h>

#include "firmware/explore/prng.hpp"
#include "tests/nn/reference_kernels.hpp"

namespace curio::nn {
namespace {

constexpr int32_t kMin = INT32_MIN;
constexpr int32_t kMax = INT32_MAX;

TEST(FixedPoint, SaturatingAddAndSub) {
  EXPECT_EQ(saturating_add(kMax, 1), kMax);
  EXPECT_EQ(saturating_add(kMin, -1), kMin);
  EXPECT_EQ(saturating_add(kMax, kMin), -1);
  EXPECT_EQ(saturating_sub(kMin, 1), kMin);
  EXPECT_EQ(saturating_sub(kMax, -1), kMax);
  EXPECT_EQ(saturating_sub(0, kMin), kMax);
  EXPECT_EQ(saturating_add(-5, 3), -2);
}

TEST(FixedPoint, DoublingHighMulSaturatesOnlyMinTimesMin) {
  EXPECT_EQ(saturating_rounding_doubling_high_mul(kMin, kMin), kMax);
  EXPECT_EQ(saturating_rounding_doubling_high_mul(kMin, kMax), -kMax);
  EXPECT_EQ(saturating_rounding_doubling_high_mul(kMax, kMax), kMax - 1);
  EXPECT_EQ(saturating_rounding_doubling_high_mul(kMin, 1), -1);
  static_assert(saturating_rounding_doubling_high_mul(1 << 30, 1 << 30) == 1 << 29);
}

TEST(FixedPoint, DoublingHighMulRoundsTiesUpward) {
  // a·b = ±2^30 is exactly ±0.5 after the division by 2^31.
  EXPECT_EQ(saturating_rounding_doubling_high_mul(1 << 30, 1), 1);
  EXPECT_EQ(saturating_rounding_doubling_high_mul(-(1 << 30), 1), 0);
  EXPECT_EQ(saturating_rounding_doubling_high_mul(3 << 29, 2), 2);      // 1.5 → 2
  EXPECT_EQ(saturating_rounding_doubling_high_mul(-(3 << 29), 2), -1);  // −1.5 → −1
  EXPECT_EQ(saturating_rounding_doubling_high_mul((1 << 30) - 1, 1), 0);
  EXPECT_EQ(saturating_rounding_doubling_high_mul(-(1 << 30) - 1, 1), -1);
}

TEST(FixedPoint, RoundingDivideTiesAwayFromZeroBothSigns) {
  EXPECT_EQ(rounding_divide_by_pot(5, 1), 3);    // 2.5
  EXPECT_EQ(rounding_divide_by_pot(-5, 1), -3);  // −2.5
  EXPECT_EQ(rounding_divide_by_pot(3, 1), 2);    // 1.5
  EXPECT_EQ(rounding_divide_by_pot(-3, 1), -2);
  EXPECT_EQ(rounding_divide_by_pot(-1, 1), -1);  // −0.5
  EXPECT_EQ(rounding_divide_by_pot(1, 1), 1);
  EXPECT_EQ(rounding_divide_by_pot(-7, 2), -2);  // −1.75
  EXPECT_EQ(rounding_divide_by_pot(7, 0), 7);
  EXPECT_EQ(rounding_divide_by_pot(kMin, 31), -1);
  EXPECT_EQ(rounding_divide_by_pot(kMax, 31), 1);
  EXPECT_EQ(rounding_divide_by_pot(1 << 30, 31), 1);      // +0.5
  EXPECT_EQ(rounding_divide_by_pot(-(1 << 30), 31), -1);  // −0.5
  EXPECT_EQ(rounding_divide_by_pot((1 << 30) - 1, 31), 0);
}

TEST(FixedPoint, MultiplyByQuantizedMultiplierOverAllShifts) {
  const int32_t half = 1 << 30;  // 0.5 in Q31
  for (int shift = -31; shift <= 30; ++shift) {
    SCOPED_TRACE(shift);
    if (shift <= 21) {  // 1000·2^shift fits in int32: exact, ties away from zero
      const double real = 1000.0 * 0.5 * std::ldexp(1.0, shift);
      const auto want = static_cast<int32_t>(std::round(real));
      EXPECT_EQ(multiply_by_quantized_multiplier(1000, half, shift), want);
      EXPECT_EQ(multiply_by_quantized_multiplier(-1000, half, shift), -want);
    } else {  // the left shift saturates: still huge, sign kept (then clamped to int8)
      EXPECT_EQ(multiply_by_quantized_multiplier(1000, half, shift), 1 << 30);
      EXPECT_EQ(multiply_by_quantized_multiplier(-1000, half, shift), -(1 << 30));
    }
  }
  EXPECT_EQ(multiply_by_quantized_multiplier(kMax, kMax, 0), kMax - 1);
  EXPECT_EQ(multiply_by_quantized_multiplier(kMin, kMin, 0), kMax);
  EXPECT_EQ(multiply_by_quantized_multiplier(kMin, kMax, -31), -1);
  EXPECT_EQ(multiply_by_quantized_multiplier(kMax, kMax, -31), 1);
  EXPECT_EQ(multiply_by_quantized_multiplier(0, kMax, 30), 0);
}

TEST(FixedPoint, MatchesDefinitionOnRandomValues) {
  Prng rng(42);
  for (int i = 0; i < 200000; ++i) {
    const auto x = static_cast<int32_t>(rng.next_u32() >> rng.below(32));
    const int32_t xs = (rng.next_u32() & 1) ? x : -x;
    const auto mult = static_cast<int32_t>((rng.next_u32() >> 1) | (1u << 30));
    const int shift = static_cast<int>(rng.below(62)) - 31;
    ASSERT_EQ(multiply_by_quantized_multiplier(xs, mult, shift), ref::mbqm(xs, mult, shift))
        << "x=" << xs << " mult=" << mult << " shift=" << shift;
    const auto a = static_cast<int32_t>(rng.next_u32());
    const auto b = static_cast<int32_t>(rng.next_u32());
    ASSERT_EQ(saturating_rounding_doubling_high_mul(a, b), ref::srdhm(a, b)) << a << " " << b;
    const int e = static_cast<int>(rng.below(32));
    ASSERT_EQ(rounding_divide_by_pot(a, e), ref::rdbp(a, e)) << a << " " << e;
  }
}

TEST(FixedPoint, RequantizeAddsZeroPointThenClamps) {
  const int32_t half = 1 << 30;
  EXPECT_EQ(requantize(100, half, 0, -128, -128, 127), -78);  // 50 − 128
  EXPECT_EQ(requantize(1000, half, 0, 0, -128, 127), 127);
  EXPECT_EQ(requantize(-1000, half, 0, 10, 10, 127), 10);  // fused ReLU at zp 10
  EXPECT_EQ(requantize(kMax, kMax, 30, 127, -128, 127), 127);
  EXPECT_EQ(requantize(kMin, kMax, 30, -128, -128, 127), -128);
}

}  // namespace
}  // namespace curio::nn

namespace curio::nn {
namespace {

// The kernels' vectorizable requantization must give requantize()'s integers in both its
// forms, including left shifts, saturating biases and rescales ≥ 0.5.
TEST(RequantizeRow, MatchesScalarRequantize) {
  Prng rng(11);
  constexpr int kCount = 64;
  for (int round = 0; round < 2000; ++round) {
    int32_t acc[kCount], acc_copy[kCount], bias[kCount], mult[kCount], shift[kCount];
    const bool extreme = round % 2 == 0;
    for (int i = 0; i < kCount; ++i) {
      acc[i] = extreme ? static_cast<int32_t>(rng.next_u32())
                       : static_cast<int32_t>(rng.below(4000001)) - 2000000;
      bias[i] = extreme ? static_cast<int32_t>(rng.next_u32())
                        : static_cast<int32_t>(rng.below(200001)) - 100000;
      mult[i] = static_cast<int32_t>((rng.next_u32() >> 1) | (1u << 30));
      shift[i] =
          extreme ? static_cast<int>(rng.below(62)) - 31 : -static_cast<int>(rng.below(20)) - 1;
      acc_copy[i] = acc[i];
    }
    const int32_t zp = static_cast<int32_t>(rng.below(256)) - 128;
    const bool simple = detail::requantize_is_simple(bias, shift, kCount, 2000000);
    if (!extreme) {
      ASSERT_TRUE(simple);
    }
    int8_t got[kCount];
    detail::requantize_row(acc, bias, mult, shift, kCount, zp, -128, 127, simple, got);
    for (int i = 0; i < kCount; ++i) {
      const int8_t want =
          requantize(saturating_add(acc_copy[i], bias[i]), mult[i], shift[i], zp, -128, 127);
      ASSERT_EQ(got[i], want) << "round " << round << " lane " << i << " acc " << acc_copy[i]
                              << " bias " << bias[i] << " mult " << mult[i] << " shift " << shift[i]
                              << " simple " << simple;
    }
  }
}

TEST(RequantizeRow, SimpleFormOnlyWhenSafe) {
  const int32_t shift_ok[2] = {-1, -20};
  const int32_t shift_zero[2] = {-1, 0};
  const int32_t small_bias[2] = {5, -5};
  const int32_t big_bias[2] = {5, INT32_MAX - 10};
  EXPECT_TRUE(detail::requantize_is_simple(small_bias, shift_ok, 2, 1 << 24));
  EXPECT_TRUE(detail::requantize_is_simple(nullptr, shift_ok, 2, 1 << 24));
  EXPECT_FALSE(detail::requantize_is_simple(small_bias, shift_zero, 2, 1 << 24));
  EXPECT_FALSE(detail::requantize_is_simple(big_bias, shift_ok, 2, 1 << 24));
}

}  // namespace
}  // namespace curio::nn
