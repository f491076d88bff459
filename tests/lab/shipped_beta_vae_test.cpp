// Integration test of the learned goal space: short MGE-βVAE explorations with the shipped int8
// β-VAE (firmware/nn/models/beta_vae_weights.hpp; skips while there is none). The outcome is the
// encoder's μ of the final image, the five modules are latent pairs in the header's KL order. What
// a user relies on: the learned goal space drives the ball far beyond random motor parameters, and
// learning progress alone singles out exactly the ball's latents (the factor report's ground
// truth), not the distractor's.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "host_tools/experiment/algorithms.hpp"
#include "host_tools/experiment/representations.hpp"
#include "host_tools/experiment/simulated_run.hpp"

namespace curio::lab {
namespace {

RunSpec spec(const char* algorithm, uint64_t seed) {
  RunSpec s;
  s.algorithm = *find_algorithm(algorithm);
  s.explorer.seed = seed;
  s.explorer.n_bootstrap = 400;  // SPEC §2 for learned goal spaces
  s.explorer.n_episodes = 3000;
  s.explorer.competence_cap = 2.0f;
  return s;
}

TEST(ShippedBetaVae, ShortMgeExplorationFindsExactlyTheBallLatents) {
  if (find_representation("beta_vae") == nullptr)
    GTEST_SKIP() << "no β-VAE weights shipped in firmware/nn/models/";
  const std::vector<int> ball = ball_latents("beta_vae");
  ASSERT_EQ(ball.size(), 2u) << "beta_vae.factor_report.json should name two ball latents";
  char expected[32];  // the verdict's spelling, e.g. "z0,z2"
  std::snprintf(expected, sizeof expected, "z%d,z%d", ball[0], ball[1]);

  for (uint64_t seed : {0u, 1u}) {
    const RunResult mge = run_exploration(spec("MGE-βVAE", seed));
    const RunResult rpe = run_exploration(spec("RPE", seed));
    ASSERT_TRUE(mge.error.empty()) << mge.error;
    ASSERT_TRUE(rpe.error.empty()) << rpe.error;
    ASSERT_EQ(mge.module_names.size(), 5u);
    EXPECT_GT(mge.ratio.back(), 3.0 * rpe.ratio.back())
        << "seed " << seed << ": MGE-βVAE " << mge.ratio.back() << ", RPE " << rpe.ratio.back();
    EXPECT_EQ(verdict_text(mge), std::string(expected)) << "seed " << seed;
  }
}

}  // namespace
}  // namespace curio::lab
