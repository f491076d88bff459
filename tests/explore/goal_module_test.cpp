#include "firmware/explore/goal_module.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "firmware/explore/distinct_outcomes.hpp"

namespace curio {
namespace {

TEST(GoalModule, ProjectsItsDimensionsInOrder) {
  GoalModule m;
  m.n_dims = 2;
  m.dims[0] = 3;
  m.dims[1] = 0;
  const float outcome[4] = {10, 11, 12, 13};
  float p[2];
  m.project(outcome, p);
  EXPECT_EQ(p[0], 13);
  EXPECT_EQ(p[1], 10);
}

TEST(GoalModule, UniformBoxGoalsCoverMinusOneToOne) {
  GoalModule m;
  m.n_dims = 4;
  m.goal_kind = GoalKind::kUniformBox;
  Prng rng(1, 2);
  float lo = 1, hi = -1;
  double sum = 0;
  constexpr int kDraws = 25000;
  for (int i = 0; i < kDraws; ++i) {
    float g[4];
    m.sample_goal(rng, g);
    for (float v : g) {
      ASSERT_GE(v, -1.0f);
      ASSERT_LE(v, 1.0f);
      lo = std::fmin(lo, v);
      hi = std::fmax(hi, v);
      sum += v;
    }
  }
  EXPECT_LT(lo, -0.999f);
  EXPECT_GT(hi, 0.999f);
  EXPECT_NEAR(sum / (4 * kDraws), 0.0, 0.01);
}

TEST(GoalModule, ClippedNormalGoalsStayInsideTheBoundAndFollowThePrior) {
  for (const float bound : {2.5f, 1.0f}) {
    GoalModule m;
    m.n_dims = 10;
    m.goal_kind = GoalKind::kClippedNormal;
    m.goal_bound = bound;
    Prng rng(3, 2);
    int at_bound = 0;
    double sum = 0, sum_sq = 0;
    constexpr int kDraws = 10000;
    for (int i = 0; i < kDraws; ++i) {
      float g[10];
      m.sample_goal(rng, g);
      for (float v : g) {
        ASSERT_GE(v, -bound);
        ASSERT_LE(v, bound);
        at_bound += std::fabs(v) == bound ? 1 : 0;
        sum += v;
        sum_sq += static_cast<double>(v) * v;
      }
    }
    const double n = 10.0 * kDraws;
    const double p_clip = std::erfc(bound / std::sqrt(2.0));  // P(|z| > bound)
    EXPECT_NEAR(at_bound / n, p_clip, 0.1 * p_clip + 0.002) << "bound " << bound;
    EXPECT_NEAR(sum / n, 0.0, 0.02);
    if (bound == 2.5f) {
      EXPECT_NEAR(sum_sq / n, 0.978, 0.02);  // E[min(z², 6.25)]
    }
  }
}

TEST(GoalModule, GoalScaleMultipliesTheClippedDrawAndOneLeavesItExact) {
  GoalModule prior, wide;
  prior.n_dims = wide.n_dims = 10;
  prior.goal_kind = wide.goal_kind = GoalKind::kClippedNormal;
  wide.goal_scale = 2.5f;
  GoalModule one = prior;
  one.goal_scale = 1.0f;
  Prng a(7, 2), b(7, 2), c(7, 2);
  for (int i = 0; i < 1000; ++i) {
    float gp[10], gw[10], g1[10];
    prior.sample_goal(a, gp);
    wide.sample_goal(b, gw);
    one.sample_goal(c, g1);
    for (int j = 0; j < 10; ++j) {
      ASSERT_EQ(gw[j], 2.5f * gp[j]);  // same draw, clipped at ±bound, then scaled
      ASSERT_LE(std::fabs(gw[j]), 2.5f * prior.goal_bound);
      ASSERT_EQ(std::memcmp(&g1[j], &gp[j], sizeof(float)), 0);
    }
  }
}

TEST(DistinctOutcomes, NeedsTwoDifferentValues) {
  DistinctOutcomes d;
  const float ball[2] = {0.6f, 0.6f};
  const float moved[2] = {0.6f, 0.61f};
  EXPECT_FALSE(d.has_two());
  d.observe(ball, 2);
  EXPECT_FALSE(d.has_two());
  for (int i = 0; i < 100; ++i) d.observe(ball, 2);
  EXPECT_FALSE(d.has_two());
  d.observe(moved, 2);
  EXPECT_TRUE(d.has_two());
  d.observe(ball, 2);
  EXPECT_TRUE(d.has_two());
  d.reset();
  EXPECT_FALSE(d.has_two());
}

}  // namespace
}  // namespace curio
