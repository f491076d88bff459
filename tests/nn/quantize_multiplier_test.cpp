// Float scale → (Q31 multiplier, shift) at its edges (TFLite's QuantizeMultiplier).
#include "firmware/nn/quantize_multiplier.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "firmware/explore/prng.hpp"

namespace curio::nn {
namespace {

QuantizedMultiplier qm(double real) {
  QuantizedMultiplier m{-1, -1};
  EXPECT_EQ(quantize_multiplier(real, &m), Status::kOk) << real;
  return m;
}

TEST(QuantizeMultiplier, PowersOfTwoAreExact) {
  EXPECT_EQ(qm(0.5).multiplier, 1 << 30);
  EXPECT_EQ(qm(0.5).shift, 0);
  EXPECT_EQ(qm(1.0).multiplier, 1 << 30);
  EXPECT_EQ(qm(1.0).shift, 1);
  EXPECT_EQ(qm(0.25).shift, -1);
  EXPECT_EQ(qm(std::ldexp(1.0, -32)).shift, -31);
}

TEST(QuantizeMultiplier, MantissaRoundingTo2Pow31MovesToNextExponent) {
  // Just below 1.0: mantissa·2^31 rounds to 2^31 → halve it, shift + 1.
  const QuantizedMultiplier m = qm(1.0 - 1e-12);
  EXPECT_EQ(m.multiplier, 1 << 30);
  EXPECT_EQ(m.shift, 1);
}

TEST(QuantizeMultiplier, RoundsHalfAwayFromZero) {
  // mantissa = 0.5 + 0.5·2^-31 sits exactly between two Q31 values.
  const double real = 0.5 + std::ldexp(1.0, -32);
  EXPECT_EQ(qm(real).multiplier, (1 << 30) + 1);
  const double below = 0.5 + std::ldexp(1.0, -33);  // a quarter step: rounds down
  EXPECT_EQ(qm(below).multiplier, 1 << 30);
}

TEST(QuantizeMultiplier, ZeroTinyHugeAndInvalid) {
  EXPECT_EQ(qm(0.0).multiplier, 0);
  EXPECT_EQ(qm(0.0).shift, 0);
  EXPECT_EQ(qm(1e-20).multiplier, 0);  // below 2^-32: rounds to nothing
  QuantizedMultiplier m{};
  EXPECT_EQ(quantize_multiplier(std::ldexp(1.0, 30), &m), Status::kOutOfRange);
  EXPECT_EQ(quantize_multiplier(std::ldexp(1.0, 30) * 0.75, &m), Status::kOk);
  EXPECT_EQ(m.shift, 30);
  EXPECT_EQ(quantize_multiplier(-0.5, &m), Status::kArgumentError);
  EXPECT_EQ(quantize_multiplier(std::numeric_limits<double>::quiet_NaN(), &m),
            Status::kArgumentError);
  EXPECT_EQ(quantize_multiplier(std::numeric_limits<double>::infinity(), &m),
            Status::kArgumentError);
  EXPECT_EQ(quantize_multiplier(0.5, nullptr), Status::kArgumentError);
}

TEST(QuantizeMultiplier, RelativeErrorBelowHalfAQ31Step) {
  Prng rng(7);
  for (int i = 0; i < 10000; ++i) {
    const double real = std::exp(rng.uniform(-20.0, 5.0));
    const QuantizedMultiplier m = qm(real);
    EXPECT_GE(m.multiplier, 1 << 30);
    EXPECT_LE(std::abs(dequantize_multiplier(m) - real) / real, std::ldexp(1.0, -31) + 1e-15);
  }
}

}  // namespace
}  // namespace curio::nn
