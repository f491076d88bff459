// The factor-report estimators on synthetic data whose answers are known in closed form.
#include "host_tools/vae/factor_metrics.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "firmware/explore/prng.hpp"

namespace curio::train {
namespace {

std::vector<double> uniform_sample(Prng& rng, int n) {
  std::vector<double> v(static_cast<size_t>(n));
  for (auto& x : v) x = rng.uniform(-1.0, 1.0);
  return v;
}

TEST(Pearson, IsOneForAnIncreasingLineAndMinusOneForADecreasingOne) {
  const std::vector<double> a = {0, 1, 2, 3, 4};
  const std::vector<double> up = {1, 3, 5, 7, 9};
  const std::vector<double> down = {4, 2, 0, -2, -4};
  EXPECT_NEAR(pearson(a, up), 1.0, 1e-12);
  EXPECT_NEAR(pearson(a, down), -1.0, 1e-12);
}

TEST(Pearson, IsZeroForAConstantInput) {
  EXPECT_EQ(pearson(std::vector<double>{1, 2, 3}, std::vector<double>{5, 5, 5}), 0.0);
}

TEST(Pearson, IsNearZeroForIndependentSamples) {
  Prng rng(3);
  const auto a = uniform_sample(rng, 20000), b = uniform_sample(rng, 20000);
  EXPECT_LT(std::abs(pearson(a, b)), 0.03);  // 4 standard errors at n = 20,000
}

TEST(Pearson, MatchesTheClosedFormForAMixture) {
  // z = x + y with x, y independent, equal variance: corr(z, x) = 1/√2.
  Prng rng(4);
  const auto x = uniform_sample(rng, 50000), y = uniform_sample(rng, 50000);
  std::vector<double> z(x.size());
  for (size_t i = 0; i < x.size(); ++i) z[i] = x[i] + y[i];
  EXPECT_NEAR(pearson(z, x), 1.0 / std::sqrt(2.0), 0.01);
}

TEST(Discretize, PutsEdgesAndOutliersInTheEndBins) {
  const std::vector<double> v = {-1.0, -0.95, 0.0, 0.999, 1.0, 7.0, -7.0};
  EXPECT_EQ(discretize(v, 20, -1.0, 1.0), (std::vector<int>{0, 0, 10, 19, 19, 19, 0}));
  EXPECT_EQ(discretize_to_range(std::vector<double>{2, 2, 2}, 20), (std::vector<int>{0, 0, 0}));
}

TEST(Entropy, OfEquallyFilledBinsIsLogOfTheirCount) {
  std::vector<int> labels;
  for (int i = 0; i < 2000; ++i) labels.push_back(i % 20);
  EXPECT_NEAR(entropy(labels, 20), std::log(20.0), 1e-12);
  EXPECT_NEAR(entropy(std::vector<int>(50, 3), 20), 0.0, 1e-12);
}

TEST(MutualInformation, OfAVariableWithItselfIsItsEntropy) {
  Prng rng(5);
  const auto x = discretize(uniform_sample(rng, 5000), 20, -1, 1);
  EXPECT_NEAR(mutual_information(x, 20, x, 20), entropy(x, 20), 1e-12);
}

TEST(MutualInformation, OfIndependentVariablesIsOnlyThePluginBias) {
  // Plug-in bias ≈ (20−1)²/(2n) = 0.018 nats at n = 10,000.
  Prng rng(6);
  const auto x = discretize(uniform_sample(rng, 10000), 20, -1, 1);
  const auto y = discretize(uniform_sample(rng, 10000), 20, -1, 1);
  EXPECT_LT(mutual_information(x, 20, y, 20), 0.03);
}

struct Synthetic {
  std::vector<std::vector<double>> factors;  // 4 factors uniform in [-1,1]
  std::vector<std::vector<double>> noise;    // 6 nuisance latents
};

Synthetic synthetic(int n) {
  Prng rng(7);
  Synthetic s;
  for (int k = 0; k < 4; ++k) s.factors.push_back(uniform_sample(rng, n));
  for (int k = 0; k < 6; ++k) {
    std::vector<double> v(static_cast<size_t>(n));
    for (auto& x : v) x = 0.01 * rng.normal();
    s.noise.push_back(v);
  }
  return s;
}

TEST(Mig, IsNearOneWhenEachLatentCopiesOneFactor) {
  const Synthetic s = synthetic(10000);
  auto latents = s.noise;
  // Monotone (not linear) copies: MI does not care, Pearson would.
  for (const auto& f : s.factors) {
    std::vector<double> z(f.size());
    for (size_t i = 0; i < f.size(); ++i) z[i] = 2.0 * f[i] + 0.5;
    latents.push_back(z);
  }
  const MigResult r = mutual_information_gap(latents, s.factors);
  EXPECT_GT(r.mig, 0.95);
  ASSERT_EQ(r.gap_per_factor.size(), 4u);
  EXPECT_NEAR(r.normalized_mi[6][0], 1.0, 0.01);
  EXPECT_LT(r.normalized_mi[6][1], 0.02);
}

TEST(Mig, IsLowWhenLatentsMixTwoFactors) {
  // z1 = x + y and z2 = x − y carry x and y fully but each shares them equally.
  const Synthetic s = synthetic(10000);
  std::vector<std::vector<double>> latents(2, std::vector<double>(10000));
  for (size_t i = 0; i < 10000; ++i) {
    latents[0][i] = s.factors[0][i] + s.factors[1][i];
    latents[1][i] = s.factors[0][i] - s.factors[1][i];
  }
  const std::vector<std::vector<double>> two = {s.factors[0], s.factors[1]};
  const MigResult r = mutual_information_gap(latents, two);
  EXPECT_LT(r.mig, 0.05);
  EXPECT_GT(r.normalized_mi[0][0], 0.1);  // information is there, just not separated
}

TEST(Mig, IsZeroWithoutInformation) {
  const Synthetic s = synthetic(10000);
  EXPECT_LT(mutual_information_gap(s.noise, s.factors).mig, 0.02);
}

}  // namespace
}  // namespace curio::train
