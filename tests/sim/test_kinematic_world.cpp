// The kinematic reference model (SPEC §1.1): poses, the grasp rule, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include "firmware/explore/motor_primitive.hpp"
#include "firmware/explore/prng.hpp"
#include "sim/kinematics.hpp"
#include "sim/scene.hpp"
#include "sim/world.hpp"
#include "tests/sim/scene_equal.hpp"

namespace curio::sim {
namespace {

std::unique_ptr<World> kinematic(double grasp_radius = 0.1, double noise = 0.1, uint64_t seed = 1) {
  WorldParams params;
  params.grasp_radius = grasp_radius;
  params.distractor_noise = noise;
  return make_world(Physics::kKinematic, params, seed);
}

void fill(float theta[kThetaDim], float value) {
  for (int i = 0; i < kThetaDim; ++i) theta[i] = value;
}

TEST(Kinematics, ZeroCommandsPutHandAtOneZero) {
  const float a[kJoints] = {};
  const Vec2 hand = forward_kinematics(a);
  EXPECT_DOUBLE_EQ(hand.x, 1.0);
  EXPECT_DOUBLE_EQ(hand.y, 0.0);
}

TEST(Kinematics, AnglesAreCumulativeSumsTimesPi) {
  // Base link up (π/2), every later joint turns back by −π/2: the rest points along +x.
  const float up_then_right[kJoints] = {0.5f, -0.5f, 0, 0, 0, 0, 0};
  Vec2 hand = forward_kinematics(up_then_right);
  EXPECT_NEAR(hand.x, 0.7, 1e-15);
  EXPECT_NEAR(hand.y, 0.3, 1e-15);
  // All links up: hand at (0, 1).
  const float up[kJoints] = {0.5f, 0, 0, 0, 0, 0, 0};
  hand = forward_kinematics(up);
  EXPECT_NEAR(hand.x, 0.0, 1e-15);
  EXPECT_NEAR(hand.y, 1.0, 1e-15);
  // Folded: first link forward, second turned back by π, the rest forward again.
  const float folded[kJoints] = {0, 1.0f, -1.0f, 0, 0, 0, 0};
  hand = forward_kinematics(folded);
  EXPECT_NEAR(hand.x, 0.3 - 0.2 + 0.5, 1e-15);
  EXPECT_NEAR(hand.y, 0.0, 1e-15);
}

TEST(KinematicWorld, ResetIsTheSpecStartState) {
  auto world = kinematic();
  world->reset();
  const SceneState& s = world->state();
  EXPECT_EQ(s.hand.x, 1.0);
  EXPECT_EQ(s.hand.y, 0.0);
  EXPECT_EQ(s.ball.x, 0.6);
  EXPECT_EQ(s.ball.y, 0.6);
  EXPECT_EQ(s.distractor.x, 0.7);
  EXPECT_EQ(s.distractor.y, -0.45);
  EXPECT_FALSE(s.grasped);
}

TEST(KinematicWorld, ZeroThetaLeavesHandAtOneZeroAndBallInPlace) {
  auto world = kinematic();
  float theta[kThetaDim];
  fill(theta, 0.0f);
  const SceneState s = world->rollout(theta);
  EXPECT_EQ(s.hand.x, 1.0);
  EXPECT_EQ(s.hand.y, 0.0);
  EXPECT_FALSE(s.grasped);
  EXPECT_EQ(s.ball.x, 0.6);
  EXPECT_EQ(s.ball.y, 0.6);
}

TEST(KinematicWorld, SaturatedThetaGivesConstantCommands) {
  // Σ_k φ_k(t) > 1 at every step, so all-ones on a joint clips to a constant command 1.
  auto world = kinematic();
  float theta[kThetaDim];
  fill(theta, 0.0f);
  for (int k = 0; k < kBasisPerJoint; ++k) theta[k] = 1.0f;  // joint 0 → +1: angle π
  SceneState s = world->rollout(theta);
  EXPECT_NEAR(s.hand.x, -1.0, 1e-15);
  EXPECT_NEAR(s.hand.y, 0.0, 1e-15);
  for (int k = 0; k < kBasisPerJoint; ++k) theta[kBasisPerJoint + k] = -1.0f;  // joint 1 → −1
  s = world->rollout(theta);
  EXPECT_NEAR(s.hand.x, -0.3 + 0.7, 1e-15);
  EXPECT_NEAR(s.hand.y, 0.0, 1e-15);
  EXPECT_FALSE(s.grasped);
}

// Hand at (cos 45°, sin 45°): its distance d to the ball decides the grasp.
constexpr float kDiagonal[kJoints] = {0.25f, 0, 0, 0, 0, 0, 0};

double diagonal_distance_to_ball() {
  const Vec2 hand = forward_kinematics(kDiagonal);
  const double dx = hand.x - kBallStart.x;
  const double dy = hand.y - kBallStart.y;
  return std::sqrt(dx * dx + dy * dy);
}

TEST(GraspRule, StrictlyInsideTheRadiusGrasps) {
  const double d = diagonal_distance_to_ball();
  ASSERT_GT(d, 0.1);  // the default radius does not reach
  auto at_radius = kinematic(d);
  at_radius->step(kDiagonal);
  EXPECT_FALSE(at_radius->state().grasped) << "distance == radius must not grasp";
  EXPECT_EQ(at_radius->state().ball.x, 0.6);

  auto just_beyond = kinematic(std::nextafter(d, 1.0));
  just_beyond->step(kDiagonal);
  EXPECT_TRUE(just_beyond->state().grasped);
  EXPECT_EQ(just_beyond->state().ball.x, just_beyond->state().hand.x);
  EXPECT_EQ(just_beyond->state().ball.y, just_beyond->state().hand.y);
}

TEST(GraspRule, BallFollowsHandAndIsNeverReleased) {
  auto world = kinematic(0.2);
  world->reset();
  world->step(kDiagonal);
  ASSERT_TRUE(world->state().grasped);
  const float away[kJoints] = {-0.5f, 0.1f, 0.2f, 0, 0, 0, 0};  // far below the ball
  world->step(away);
  const SceneState& s = world->state();
  EXPECT_TRUE(s.grasped);
  EXPECT_EQ(s.ball.x, s.hand.x);
  EXPECT_EQ(s.ball.y, s.hand.y);
  EXPECT_LT(s.ball.y, 0.0);
  world->reset();
  EXPECT_FALSE(world->state().grasped);
  EXPECT_EQ(world->state().ball.x, 0.6);
}

TEST(GraspRule, FinalBallIsFinalHandOrStart) {
  // Over random θ: grasped → ball == hand(49); otherwise ball exactly at (0.6, 0.6).
  auto world = kinematic();
  Prng rng(42);
  int grasps = 0;
  float theta[kThetaDim];
  for (int e = 0; e < 3000; ++e) {
    for (float& v : theta) v = static_cast<float>(rng.uniform(-1.0, 1.0));
    const SceneState s = world->rollout(theta);
    if (s.grasped) {
      ++grasps;
      EXPECT_EQ(s.ball.x, s.hand.x);
      EXPECT_EQ(s.ball.y, s.hand.y);
    } else {
      EXPECT_EQ(s.ball.x, 0.6);
      EXPECT_EQ(s.ball.y, 0.6);
    }
  }
  // SPEC: about 1.9 % of uniformly random θ grasp.
  std::printf("random-θ grasp rate: %.2f %%\n", 100.0 * grasps / 3000.0);
  EXPECT_GT(grasps, 3000 * 0.01);
  EXPECT_LT(grasps, 3000 * 0.03);
}

TEST(KinematicWorld, RolloutIsResetPlusFiftySteps) {
  auto a = kinematic(0.1, 0.1, 9);
  auto b = kinematic(0.1, 0.1, 9);
  Prng rng(3);
  float theta[kThetaDim];
  for (float& v : theta) v = static_cast<float>(rng.uniform(-1.0, 1.0));
  const SceneState sa = a->rollout(theta);
  const MotorPrimitive primitive;
  b->reset();
  float commands[kJoints];
  for (int t = 0; t < kStepsPerEpisode; ++t) {
    primitive.commands(theta, t, commands);
    b->step(commands);
  }
  EXPECT_TRUE(identical(sa, b->state()));
}

}  // namespace
}  // namespace curio::sim
