// The controllable-feature statistic on synthetic progress traces with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "firmware/explore/prng.hpp"
#include "host_tools/experiment/controllability.hpp"

namespace curio::lab {
namespace {

struct SimRun {
  std::vector<ProgressSample> exploits;
  std::vector<std::vector<float>> interest;
  std::vector<int> episodes;
};

// Modules with progress p = drift + noise·N(0,1) at their exploits (one exploit every 5
// episodes, module chosen round-robin), cp smoothed with W = 1000, sampled every 50 episodes.
SimRun simulate(const std::vector<std::pair<double, double>>& modules, uint64_t seed,
             int episodes = 10100) {
  Prng rng(seed);
  SimRun r;
  std::vector<double> cp(modules.size(), 1e-5);
  int turn = 0;
  for (int e = 1; e <= episodes; ++e) {
    if (e > 100 && e % 5 == 0) {
      const size_t k = static_cast<size_t>(turn++) % modules.size();
      const double p = modules[k].first + modules[k].second * rng.normal();
      cp[k] += (p - cp[k]) / 1000.0;
      r.exploits.push_back({e, static_cast<int>(k), static_cast<float>(p)});
    }
    if (e % 50 == 0) {
      std::vector<float> row;
      for (double c : cp) row.push_back(static_cast<float>(std::fabs(c)));
      r.interest.push_back(row);
      r.episodes.push_back(e);
    }
  }
  return r;
}

std::vector<ModuleVerdict> classify(const SimRun& r) {
  return classify_modules(r.exploits, r.interest, r.episodes, 100, 10100);
}

TEST(Controllability, BallLikeModuleIsControllableDistractorLikeIsNot) {
  for (uint64_t seed = 0; seed < 20; ++seed) {
    const auto v = classify(simulate({{0.0, 0.6}, {0.04, 0.1}}, seed));
    ASSERT_EQ(v.size(), 2u);
    EXPECT_FALSE(v[0].controllable) << "seed " << seed << " t " << v[0].t;
    EXPECT_TRUE(v[1].controllable) << "seed " << seed << " t " << v[1].t;
    EXPECT_NEAR(v[1].mean_progress, 0.04, 0.01);
    EXPECT_GT(v[1].exploits, 400);
  }
}

TEST(Controllability, ZeroMeanProgressIsRarelyControllable) {
  int flagged = 0;
  for (uint64_t seed = 0; seed < 100; ++seed)
    for (const auto& m : classify(simulate({{0.0, 0.5}, {0.0, 0.5}}, seed))) flagged += m.controllable;
  EXPECT_LE(flagged, 2);  // t ≥ 3 by chance: ~0.1 % per module
}

TEST(Controllability, NegligibleConsistentProgressIsDropped) {
  const auto v = classify(simulate({{0.05, 0.05}, {0.002, 0.0001}}, 1));
  EXPECT_TRUE(v[0].controllable);
  EXPECT_GT(v[1].t, 3.0);
  EXPECT_LT(v[1].relative_interest, 0.1);
  EXPECT_FALSE(v[1].controllable);
}

TEST(Controllability, JudgesOnlyTheSecondHalfAfterTheBootstrap) {
  SimRun r;
  for (int e = 105; e <= 10100; e += 5) r.exploits.push_back({e, 0, e < 5100 ? -0.05f : 0.05f});
  for (int e = 50; e <= 10100; e += 50) {
    r.interest.push_back({0.05f});
    r.episodes.push_back(e);
  }
  const auto v = classify(r);
  EXPECT_TRUE(v[0].controllable);
  EXPECT_NEAR(v[0].mean_progress, 0.05, 1e-6);
  EXPECT_TRUE(classify_modules({}, {}, {}, 0, 100).empty());
}

TEST(Controllability, LatentsOfControllableModules) {
  std::vector<ModuleVerdict> v(3);
  v[0].controllable = true;
  v[2].controllable = true;
  EXPECT_EQ(controllable_latents(v, {{7, 2}, {0, 1}, {5, 3}}), (std::vector<int>{2, 3, 5, 7}));
}

}  // namespace
}  // namespace curio::lab
