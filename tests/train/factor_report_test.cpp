// The pass/fail verdict of the factor report against its criteria (docs/training.md).
#include "host_tools/vae/factor_report.hpp"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "firmware/explore/prng.hpp"

namespace curio::train {
namespace {

constexpr int kN = 4000;

std::vector<std::vector<double>> factors() {
  Prng rng(11);
  std::vector<std::vector<double>> f(4, std::vector<double>(kN));
  for (auto& col : f)
    for (auto& x : col) x = rng.uniform(-1.0, 1.0);
  return f;
}

// Latent l < 4 follows factor perm[l] through a monotone squash plus noise; the others are
// collapsed (tiny noise, KL ≈ 0).
std::vector<std::vector<double>> disentangled(const std::vector<std::vector<double>>& f) {
  Prng rng(12);
  std::vector<std::vector<double>> mu(10, std::vector<double>(kN));
  const int perm[4] = {2, 0, 3, 1};
  for (int l = 0; l < 10; ++l)
    for (int i = 0; i < kN; ++i)
      mu[l][i] = l < 4 ? 1.8 * std::tanh(1.2 * f[perm[l]][i]) + 0.05 * rng.normal()
                       : 0.001 * rng.normal();
  return mu;
}

const std::vector<double> kKlDisentangled = {3.2, 3.1, 3.3, 3.0, 0.01, 0, 0, 0, 0.002, 0};

bool mentions(const FactorReport& r, const std::string& word) {
  for (const auto& why : r.reasons)
    if (why.find(word) != std::string::npos) return true;
  return false;
}

TEST(FactorReport, PassesADisentangledBetaVae) {
  const auto f = factors();
  const FactorReport r = make_factor_report("beta-vae", kKlDisentangled, disentangled(f), f);
  EXPECT_TRUE(r.pass) << summary_text(r);
  EXPECT_EQ(r.active, (std::vector<int>{2, 0, 1, 3}));  // by decreasing KL
  EXPECT_EQ(r.best_factor[0], 2);
  EXPECT_GT(r.mig_all.mig, 0.4);
  const auto j = to_json(r);
  EXPECT_EQ(j.at("pass"), true);
  EXPECT_EQ(j.at("active_count"), 4);
  EXPECT_EQ(j.at("latents").size(), 10u);
}

TEST(FactorReport, FailsABetaVaeWithAMixedLatent) {
  const auto f = factors();
  auto mu = disentangled(f);
  for (int i = 0; i < kN; ++i) mu[0][i] = f[2][i] + f[0][i];  // distractor x + ball x
  const FactorReport r = make_factor_report("beta-vae", kKlDisentangled, mu, f);
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(mentions(r, "z0")) << summary_text(r);
}

TEST(FactorReport, FailsABetaVaeWithTheWrongNumberOfActiveLatents) {
  const auto f = factors();
  auto kl = kKlDisentangled;
  kl[5] = 0.8;
  const FactorReport r = make_factor_report("beta-vae", kl, disentangled(f), f);
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(mentions(r, "5 active latents")) << summary_text(r);
}

TEST(FactorReport, FailsABetaVaeThatMissesAFactor) {
  const auto f = factors();
  auto mu = disentangled(f);
  mu[3] = mu[1];  // two latents for ball x, none for ball y
  const FactorReport r = make_factor_report("beta-vae", kKlDisentangled, mu, f);
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(mentions(r, "no clean latent for ball_y")) << summary_text(r);
}

TEST(FactorReport, PassesAnEntangledVaeAndFailsADisentangledOne) {
  const auto f = factors();
  Prng rng(13);
  // Ten random mixtures of the four factors.
  std::vector<std::vector<double>> mu(10, std::vector<double>(kN, 0.0));
  for (auto& col : mu) {
    double w[4];
    for (auto& x : w) x = rng.normal();
    for (int i = 0; i < kN; ++i)
      for (int k = 0; k < 4; ++k) col[i] += w[k] * f[k][i];
  }
  const std::vector<double> kl(10, 2.3);
  const FactorReport entangled = make_factor_report("vae", kl, mu, f);
  EXPECT_TRUE(entangled.pass) << summary_text(entangled);

  const FactorReport clean = make_factor_report("vae", kl, disentangled(f), f);
  EXPECT_FALSE(clean.pass);
}

}  // namespace
}  // namespace curio::train
