#include "firmware/explore/sparse_goal.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "tests/explore/toy_environment.hpp"

namespace curio {
namespace {

// 50 episodes that left the "ball" at rest (0.6, 0.6), two near each other and one alone.
std::unique_ptr<Archive> rest_heavy_archive() {
  auto a = std::make_unique<Archive>();
  a->reset(2, ThetaGenerator{});
  const float rest[2] = {0.6f, 0.6f}, near_a[2] = {0.0f, 0.0f}, near_b[2] = {0.1f, 0.0f},
              alone[2] = {-0.9f, 0.9f};
  for (int i = 0; i < 50; ++i) a->append(ThetaRecipe{}, rest);
  a->append(ThetaRecipe{}, near_a);  // 50
  a->append(ThetaRecipe{}, near_b);  // 51
  a->append(ThetaRecipe{}, alone);   // 52
  return a;
}

GoalModule both_dims() {
  GoalModule m;
  m.n_dims = 2;
  m.dims[0] = 0;
  m.dims[1] = 1;
  return m;
}

TEST(SparseGoal, NearestOtherDistanceSkipsTheEntryItself) {
  const auto a = rest_heavy_archive();
  const GoalModule m = both_dims();
  EXPECT_EQ(nearest_other_distance_sq(*a, m, 3), 0.0f);  // a duplicate of "rest"
  EXPECT_NEAR(nearest_other_distance_sq(*a, m, 50), 0.01f, 1e-6f);
  // "alone" (-0.9, 0.9) is nearest to (0, 0): 0.81 + 0.81.
  EXPECT_NEAR(nearest_other_distance_sq(*a, m, 52), 1.62f, 1e-5f);
  EXPECT_EQ(nearest_other_distance_sq(*a, m, 53), -1.0f);
  EXPECT_EQ(nearest_other_distance_sq(*a, m, -1), -1.0f);
}

// Share of 4,000 goals that are the lone outcome, with `candidates` draws per goal.
double lone_goal_share(int candidates) {
  const auto a = rest_heavy_archive();
  const GoalModule m = both_dims();
  Prng rng(3, 2);
  int lone = 0;
  for (int t = 0; t < 4000; ++t) {
    float g[2];
    const int i = sparse_archive_goal(*a, m, candidates, rng, g);
    EXPECT_GE(i, 0);
    // The goal is exactly the chosen entry's outcome.
    EXPECT_EQ(g[0], a->outcome(i, 0));
    EXPECT_EQ(g[1], a->outcome(i, 1));
    lone += i == 52 ? 1 : 0;
  }
  return lone / 4000.0;
}

TEST(SparseGoal, GoalsGoWhereReachedOutcomesAreSparse) {
  // One candidate: the goal is a uniform archive entry (1/53). 16 candidates: the lone outcome
  // wins whenever it is drawn, 1 − (52/53)^16 ≈ 0.26; 64 candidates: ≈ 0.70.
  EXPECT_NEAR(lone_goal_share(1), 1.0 / 53, 0.01);
  EXPECT_NEAR(lone_goal_share(16), 1.0 - std::pow(52.0 / 53, 16), 0.03);
  EXPECT_NEAR(lone_goal_share(64), 1.0 - std::pow(52.0 / 53, 64), 0.03);
}

TEST(SparseGoal, EmptyArchiveOrNoCandidatesDrawsNothing) {
  Archive a;
  a.reset(2, ThetaGenerator{});
  const GoalModule m = both_dims();
  Prng rng(1, 2), untouched(1, 2);
  float g[2] = {7.0f, 7.0f};
  EXPECT_EQ(sparse_archive_goal(a, m, 8, rng, g), -1);
  const auto b = rest_heavy_archive();
  EXPECT_EQ(sparse_archive_goal(*b, m, 0, rng, g), -1);
  EXPECT_EQ(g[0], 7.0f);
  EXPECT_EQ(rng.next_u32(), untouched.next_u32());
}

TEST(SparseGoal, ExplorerConfigChecksTheCandidateCount) {
  ExplorerConfig c;
  const uint8_t kl_order[kLatentDim] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  ASSERT_EQ(set_latent_modules(c, kl_order, 2), Status::kOk);
  c.goal_kind = GoalKind::kSparseArchive;
  EXPECT_EQ(validate(c), Status::kOk);
  for (const int bad : {0, -1, kMaxGoalCandidates + 1}) {
    c.goal_candidates = bad;
    EXPECT_EQ(validate(c), Status::kInvalidConfig) << bad;
  }
}

// The Explorer with sparse goals: every goal is a reached module outcome, and the run repeats
// bit for bit.
TEST(SparseGoal, ExplorerGoalsAreReachedOutcomesAndTheRunRepeatsBitForBit) {
  const uint8_t kl_order[kLatentDim] = {2, 3, 0, 1, 4, 5, 6, 7, 8, 9};
  auto run = [&](Explorer& e, uint32_t* checksum) {
    ExplorerConfig c;
    ASSERT_EQ(set_latent_modules(c, kl_order, 2), Status::kOk);
    c.goal_kind = GoalKind::kSparseArchive;
    c.n_bootstrap = 200;
    c.n_episodes = 500;
    c.seed = 5;
    ASSERT_EQ(e.init(c), Status::kOk);
    float theta[kThetaDim], outcome[kLatentDim];
    uint32_t h = 2166136261u;
    int goals_checked = 0;
    while (!e.done()) {
      const int before = e.archive().size();
      ASSERT_EQ(e.propose(theta), Status::kOk);
      if (e.kind() == EpisodeKind::kExplore && e.module() >= 0 &&
          (e.episode() - c.n_bootstrap) % 5 == 0) {
        bool found = false;
        const int k = e.module();
        for (int i = 0; i < before && !found; ++i) {
          found = e.archive().outcome(i, c.modules[k].dims[0]) == e.goal()[0] &&
                  e.archive().outcome(i, c.modules[k].dims[1]) == e.goal()[1];
        }
        EXPECT_TRUE(found) << "episode " << e.episode();
        ++goals_checked;
      }
      for (float v : theta) {
        uint32_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        h = (h ^ bits) * 16777619u;
      }
      test::toy_latent_outcome(theta, outcome);
      ASSERT_EQ(e.observe(outcome), Status::kOk);
    }
    EXPECT_EQ(goals_checked, 100);
    *checksum = h;
  };
  auto a = std::make_unique<Explorer>();
  auto b = std::make_unique<Explorer>();
  uint32_t ha = 0, hb = 1;
  run(*a, &ha);
  run(*b, &hb);
  EXPECT_EQ(ha, hb);
}

}  // namespace
}  // namespace curio
