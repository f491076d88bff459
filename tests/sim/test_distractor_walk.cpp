// The distractor's random walk (SPEC §1.1 step 4) and the world's determinism.
#include <gtest/gtest.h>

#include <cmath>

#include "firmware/explore/motor_primitive.hpp"
#include "firmware/explore/prng.hpp"
#include "sim/distractor_walk.hpp"
#include "sim/scene.hpp"
#include "sim/world.hpp"
#include "tests/sim/scene_equal.hpp"

namespace curio::sim {
namespace {

TEST(DistractorWalk, ZeroNoiseKeepsItFixed) {
  DistractorWalk walk(0.0, 5);
  for (int t = 0; t < 500; ++t) walk.step();
  EXPECT_EQ(walk.position().x, 0.7);
  EXPECT_EQ(walk.position().y, -0.45);
}

TEST(DistractorWalk, ClippedToTheBox) {
  DistractorWalk walk(10.0, 5);  // huge steps: almost every step clips
  int at_bound = 0;
  for (int t = 0; t < 1000; ++t) {
    walk.step();
    const Vec2 p = walk.position();
    ASSERT_LE(std::fabs(p.x), 0.95);
    ASSERT_LE(std::fabs(p.y), 0.95);
    at_bound += std::fabs(p.x) == 0.95;
  }
  EXPECT_GT(at_bound, 900);
}

TEST(DistractorWalk, IncrementsHaveTheConfiguredSpread) {
  DistractorWalk walk(0.1, 11);
  double sum_sq = 0.0;
  int n = 0;
  for (int episode = 0; episode < 400; ++episode) {
    walk.reset();
    for (int t = 0; t < kStepsPerEpisode; ++t) {
      const Vec2 before = walk.position();
      walk.step();
      const Vec2 after = walk.position();
      if (std::fabs(after.x) < 0.95 && std::fabs(after.y) < 0.95) {  // unclipped steps only
        sum_sq += (after.x - before.x) * (after.x - before.x) +
                  (after.y - before.y) * (after.y - before.y);
        n += 2;
      }
    }
  }
  EXPECT_NEAR(std::sqrt(sum_sq / n), 0.1, 0.003);
}

TEST(DistractorWalk, ResetReturnsToStartButStreamContinues) {
  DistractorWalk walk(0.1, 3);
  walk.step();
  const Vec2 first = walk.position();
  walk.reset();
  EXPECT_EQ(walk.position().x, 0.7);
  EXPECT_EQ(walk.position().y, -0.45);
  walk.step();
  EXPECT_NE(walk.position().x, first.x);
}

// Episode e's walk from the seed alone equals the walk after e episodes of 50 steps (PCG
// jump-ahead): what lets curio-sim serve replay or resume any episode exactly.
TEST(DistractorWalk, ResetToEpisodeEqualsTheWalkAfterThatManyEpisodes) {
  DistractorWalk unbroken(0.1, 11);
  for (int e = 0; e < 40; ++e) {
    unbroken.reset();
    DistractorWalk positioned(0.1, 11);
    for (int k = 0; k < 3; ++k) positioned.step();  // whatever it did before
    positioned.reset_to_episode(static_cast<uint64_t>(e));
    EXPECT_EQ(positioned.position().x, 0.7);
    for (int t = 0; t < kStepsPerEpisode; ++t) {
      unbroken.step();
      positioned.step();
      ASSERT_EQ(positioned.position().x, unbroken.position().x) << "episode " << e << " step " << t;
      ASSERT_EQ(positioned.position().y, unbroken.position().y) << "episode " << e << " step " << t;
    }
  }
  DistractorWalk still(0.0, 11);  // no noise: nothing drawn, nothing to skip
  still.reset_to_episode(1000);
  still.step();
  EXPECT_EQ(still.position().x, 0.7);
}

void random_theta(Prng* rng, float theta[kThetaDim]) {
  for (int i = 0; i < kThetaDim; ++i) theta[i] = static_cast<float>(rng->uniform(-1.0, 1.0));
}

class WorldDeterminism : public ::testing::TestWithParam<Physics> {};

TEST_P(WorldDeterminism, SameSeedSameEpisodesBitForBit) {
  auto a = make_world(GetParam(), {}, 77);
  auto b = make_world(GetParam(), {}, 77);
  Prng rng(1);
  float theta[kThetaDim];
  for (int e = 0; e < 50; ++e) {
    random_theta(&rng, theta);
    ASSERT_TRUE(identical(a->rollout(theta), b->rollout(theta))) << "episode " << e;
  }
}

TEST_P(WorldDeterminism, DifferentSeedsGiveDifferentDistractors) {
  auto a = make_world(GetParam(), {}, 1);
  auto b = make_world(GetParam(), {}, 2);
  float theta[kThetaDim] = {};
  const SceneState sa = a->rollout(theta);
  const SceneState sb = b->rollout(theta);
  EXPECT_NE(sa.distractor.x, sb.distractor.x);
  EXPECT_NE(sa.distractor.y, sb.distractor.y);
}

TEST_P(WorldDeterminism, DistractorStreamAdvancesAcrossEpisodes) {
  auto world = make_world(GetParam(), {}, 1);
  float theta[kThetaDim] = {};
  const SceneState first = world->rollout(theta);
  const SceneState second = world->rollout(theta);
  EXPECT_NE(first.distractor.x, second.distractor.x);
}

// A world positioned at episode e (a fresh one: a restarted curio-sim serve) gives the same
// episode as one that ran episodes 0..e-1 first, bit for bit, in both physics.
TEST_P(WorldDeterminism, ResetToEpisodeGivesTheSameEpisodeInAFreshWorld) {
  auto unbroken = make_world(GetParam(), {}, 5);
  Prng rng(4);
  float theta[kThetaDim];
  const MotorPrimitive primitive;
  float a[kJoints];
  for (int e = 0; e < 12; ++e) {
    random_theta(&rng, theta);
    const SceneState want = unbroken->rollout(theta);
    auto fresh = make_world(GetParam(), {}, 5);
    fresh->reset_to_episode(static_cast<uint64_t>(e));
    for (int t = 0; t < kStepsPerEpisode; ++t) {
      primitive.commands(theta, t, a);
      fresh->step(a);
    }
    ASSERT_TRUE(identical(fresh->state(), want)) << "episode " << e;
  }
}

INSTANTIATE_TEST_SUITE_P(BothPhysics, WorldDeterminism,
                         ::testing::Values(Physics::kKinematic, Physics::kOde),
                         [](const auto& info) { return std::string(physics_name(info.param)); });

TEST(WorldDeterminism, BothPhysicsDrawTheSameDistractorSequence) {
  auto kin = make_world(Physics::kKinematic, {}, 123);
  auto ode = make_world(Physics::kOde, {}, 123);
  Prng rng(2);
  float theta[kThetaDim];
  for (int e = 0; e < 20; ++e) {
    random_theta(&rng, theta);
    kin->reset();
    ode->reset();
    const MotorPrimitive primitive;
    float a[kJoints];
    for (int t = 0; t < kStepsPerEpisode; ++t) {
      primitive.commands(theta, t, a);
      kin->step(a);
      ode->step(a);
      ASSERT_EQ(kin->state().distractor.x, ode->state().distractor.x);
      ASSERT_EQ(kin->state().distractor.y, ode->state().distractor.y);
    }
  }
}

TEST(Physics, NamesRoundTrip) {
  for (Physics p : {Physics::kKinematic, Physics::kOde}) {
    Physics parsed{};
    ASSERT_TRUE(parse_physics(physics_name(p), &parsed));
    EXPECT_EQ(parsed, p);
  }
  Physics parsed{};
  EXPECT_FALSE(parse_physics("mujoco", &parsed));
}

}  // namespace
}  // namespace curio::sim
