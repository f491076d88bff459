#include "firmware/explore/module_choice.hpp"

#include <gtest/gtest.h>

namespace curio {
namespace {

// Frequencies over many draws with a fixed seed (deterministic: cannot flake). Bands are
// ±0.006, about 4 standard deviations at 100,000 draws.
void expect_frequencies(const float* interest, int n, float eps, const double* expected) {
  Prng rng(2024, 1);
  constexpr int kDraws = 100000;
  int count[10] = {};
  for (int i = 0; i < kDraws; ++i) {
    const int k = choose_module(interest, n, eps, rng);
    ASSERT_GE(k, 0);
    ASSERT_LT(k, n);
    ++count[k];
  }
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR(count[k] / static_cast<double>(kDraws), expected[k], 0.006) << "module " << k;
    EXPECT_NEAR(module_probability(interest, n, eps, k), expected[k], 1e-7) << "module " << k;
  }
}

TEST(ModuleChoice, EpsilonProportionalToInterest) {
  const float interest[4] = {0.3f, 0.1f, 0.0f, 0.6f};
  // p(i) = 0.9·I_i/1.0 + 0.1/4
  const double expected[4] = {0.295, 0.115, 0.025, 0.565};
  expect_frequencies(interest, 4, 0.1f, expected);
}

TEST(ModuleChoice, UniformWhenAllInterestsAreZero) {
  const float interest[5] = {0, 0, 0, 0, 0};
  const double expected[5] = {0.2, 0.2, 0.2, 0.2, 0.2};
  expect_frequencies(interest, 5, 0.1f, expected);
}

TEST(ModuleChoice, EpsilonOneIsUniformAndZeroIsPurelyProportional) {
  const float interest[2] = {1e-5f, 3e-5f};
  const double uniform[2] = {0.5, 0.5};
  expect_frequencies(interest, 2, 1.0f, uniform);
  const double proportional[2] = {0.25, 0.75};
  expect_frequencies(interest, 2, 0.0f, proportional);
  const float one_hot[3] = {0.0f, 0.2f, 0.0f};
  const double only_one[3] = {0.0, 1.0, 0.0};
  expect_frequencies(one_hot, 3, 0.0f, only_one);
}

TEST(ModuleChoice, SingleModuleIsAlwaysChosen) {
  const float interest[1] = {0.5f};
  Prng rng(5, 1);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(choose_module(interest, 1, 0.1f, rng), 0);
}

}  // namespace
}  // namespace curio
