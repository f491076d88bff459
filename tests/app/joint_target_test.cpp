// The one joint-target quantization (firmware/app/joint_target.hpp) and the World extension
// that the parity of bus and in-process runs rests on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "firmware/app/joint_target.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/cia402_motion.hpp"
#include "firmware/explore/motor_primitive.hpp"
#include "firmware/explore/prng.hpp"
#include "sim/world.hpp"

namespace curio::app {
namespace {

TEST(JointTarget, CommandsBecomeMicroradianCounts) {
  int32_t c = 0;
  ASSERT_EQ(command_to_counts(1.0f, &c), protocol::CodecStatus::kOk);
  EXPECT_EQ(c, 3141593);  // round(π·1e6)
  EXPECT_EQ(c, kJointLimitCounts);
  ASSERT_EQ(command_to_counts(-1.0f, &c), protocol::CodecStatus::kOk);
  EXPECT_EQ(c, -3141593);
  ASSERT_EQ(command_to_counts(0.0f, &c), protocol::CodecStatus::kOk);
  EXPECT_EQ(c, 0);
  ASSERT_EQ(command_to_counts(0.25f, &c), protocol::CodecStatus::kOk);
  EXPECT_EQ(c, 785398);  // π/4 = 0.78539816 rad
  EXPECT_EQ(command_to_counts(std::numeric_limits<float>::quiet_NaN(), &c),
            protocol::CodecStatus::kOutOfRange);
  EXPECT_TRUE(within_joint_limits(kJointLimitCounts));
  EXPECT_FALSE(within_joint_limits(kJointLimitCounts + 1));
  EXPECT_FALSE(within_joint_limits(-kJointLimitCounts - 1));
}

// The speed limit Curio's controller writes (0x607F = 0x6080 = od::kConfigMaxVelocityCounts)
// and the joint range (0x607D = ±kJointLimitCounts) never limit a target of the motor
// primitive, whatever θ: the first step of an episode goes from the start pose (0) to a
// command within [−1, 1] (at most π rad, the whole limit per 10 ms period), every later step
// changes a command by at most Σ_k |φ_k(t) − φ_k(t−1)| (the clip does not widen a step), and
// the return to the start pose is at most π. So the drives' limits leave every result as it
// was (the golden checksums included).
TEST(JointTarget, TheConfiguredSpeedLimitNeverLimitsAPrimitiveStep) {
  const int64_t max_step = protocol::cia402::max_step_counts(protocol::od::kConfigMaxVelocityCounts,
                                                              /*period_us=*/10'000);
  EXPECT_GE(max_step, kJointLimitCounts) << "the first step and the return: up to π";
  const MotorPrimitive primitive;
  double widest = 0;
  for (int t = 1; t < kStepsPerEpisode; ++t) {
    double change = 0;
    for (int k = 0; k < kBasisPerJoint; ++k)
      change += std::fabs(static_cast<double>(primitive.basis(t, k)) - primitive.basis(t - 1, k));
    widest = std::max(widest, change);
  }
  const double widest_counts = kPi * widest * 1e6;
  EXPECT_LT(widest_counts + 1, static_cast<double>(max_step));
  EXPECT_NEAR(kPi * widest, 0.864, 0.001) << "rad per period after the first step, at most";
  // Targets a drive's 0x607D would clamp are never sent: every command maps within the range.
  int32_t c = 0;
  ASSERT_EQ(command_to_counts(-1.0f, &c), protocol::CodecStatus::kOk);
  EXPECT_EQ(c, -kJointLimitCounts);
}

TEST(JointTarget, QuantizedAnglesRoundTripThroughCounts) {
  const float a[kJoints] = {1.0f, -1.0f, 0.0f, 0.5f, -0.123456f, 1e-9f, 0.3333f};
  double rad[kJoints];
  ASSERT_TRUE(quantized_joint_angles(a, rad));
  for (int j = 0; j < kJoints; ++j) {
    int32_t c = 0;
    command_to_counts(a[j], &c);
    EXPECT_EQ(rad[j], protocol::counts_to_angle(c));
    EXPECT_NEAR(rad[j], kPi * a[j], 0.5e-6 + 1e-15);
  }
  float bad[kJoints] = {};
  bad[3] = std::numeric_limits<float>::quiet_NaN();
  rad[3] = 42.0;
  EXPECT_FALSE(quantized_joint_angles(bad, rad));
  EXPECT_EQ(rad[3], 42.0) << "untouched on failure";
  bad[3] = 1.5f;  // outside [−1, 1]: beyond the joint range
  EXPECT_FALSE(quantized_joint_angles(bad, rad));
}

void random_theta(Prng* rng, float* theta) {
  for (int i = 0; i < kThetaDim; ++i) theta[i] = static_cast<float>(rng->uniform(-1.0, 1.0));
}

// The quantized rollout stays the paper's arm: grasp decisions and final positions agree
// with the exact model (kinematic), and the ODE arm agrees with the kinematic one (SPEC §1.3).
TEST(WorldJointTargets, QuantizedRolloutAgreesWithExactModelAndAcrossPhysics) {
  auto exact = sim::make_world(sim::Physics::kKinematic, {}, 5);
  auto kin = sim::make_world(sim::Physics::kKinematic, {}, 5);
  auto ode = sim::make_world(sim::Physics::kOde, {}, 5);
  Prng rng(77);
  float theta[kThetaDim];
  constexpr int kEpisodes = 600;
  int agree_exact = 0, agree_ode = 0, grasps = 0;
  double max_hand_exact = 0, max_ball_ode = 0;
  for (int e = 0; e < kEpisodes; ++e) {
    random_theta(&rng, theta);
    const sim::SceneState x = exact->rollout(theta);
    const sim::SceneState k = kin->rollout_joint_targets(theta);
    const sim::SceneState o = ode->rollout_joint_targets(theta);
    agree_exact += x.grasped == k.grasped;
    agree_ode += k.grasped == o.grasped;
    grasps += k.grasped;
    max_hand_exact = std::max(max_hand_exact, std::hypot(x.hand.x - k.hand.x, x.hand.y - k.hand.y));
    if (k.grasped && o.grasped)
      max_ball_ode = std::max(max_ball_ode, std::hypot(k.ball.x - o.ball.x, k.ball.y - o.ball.y));
    EXPECT_EQ(x.distractor.x, k.distractor.x);  // the same walk
  }
  std::printf(
      "quantized vs exact: grasp agreement %d/%d, max hand difference %.3g; ODE vs kinematic "
      "(quantized): %d/%d, max ball difference %.3g; %d grasps\n",
      agree_exact, kEpisodes, max_hand_exact, agree_ode, kEpisodes, max_ball_ode, grasps);
  EXPECT_GE(agree_exact, kEpisodes * 99 / 100);
  EXPECT_LT(max_hand_exact, 1e-5);  // ≤ 7 joints × 0.5 µrad
  EXPECT_GE(agree_ode, kEpisodes * 99 / 100);
  EXPECT_LT(max_ball_ode, 0.01);
  EXPECT_GT(grasps, 0);
}

// replay_episode() runs the last episode again exactly (a retried episode over the bus).
TEST(WorldJointTargets, ReplayRepeatsTheLastEpisodeExactly) {
  for (sim::Physics p : {sim::Physics::kKinematic, sim::Physics::kOde}) {
    auto w = sim::make_world(p, {}, 9);
    auto reference = sim::make_world(p, {}, 9);
    Prng rng(3);
    float theta[kThetaDim];
    for (int e = 0; e < 20; ++e) {
      random_theta(&rng, theta);
      const sim::SceneState want = reference->rollout_joint_targets(theta);
      // A partial first attempt, then the replay: same final state as the reference.
      w->reset();
      const double half[kJoints] = {0.1, -0.2, 0.3, 0, 0, 0, 0.5};
      for (int t = 0; t < 17; ++t) w->step_joint_angles(half);
      w->replay_episode();
      const sim::SceneState& s0 = w->state();
      EXPECT_EQ(s0.distractor.x, 0.7);
      EXPECT_FALSE(s0.grasped);
      const MotorPrimitive primitive;
      float a[kJoints];
      double rad[kJoints];
      for (int t = 0; t < kStepsPerEpisode; ++t) {
        primitive.commands(theta, t, a);
        ASSERT_TRUE(quantized_joint_angles(a, rad));
        w->step_joint_angles(rad);
      }
      const sim::SceneState& got = w->state();
      ASSERT_EQ(got.ball.x, want.ball.x) << sim::physics_name(p) << " episode " << e;
      ASSERT_EQ(got.ball.y, want.ball.y);
      ASSERT_EQ(got.distractor.x, want.distractor.x);
      ASSERT_EQ(got.distractor.y, want.distractor.y);
      ASSERT_EQ(got.hand.x, want.hand.x);
      ASSERT_EQ(got.grasped, want.grasped);
    }
  }
}

TEST(WorldJointTargets, JointAnglesReadBackWhatWasCommanded) {
  for (sim::Physics p : {sim::Physics::kKinematic, sim::Physics::kOde}) {
    auto w = sim::make_world(p, {}, 1);
    const double rad[kJoints] = {0.5, -1.0, 3.0, -3.1, 0.0, 1e-6, 2.5};
    w->step_joint_angles(rad);
    for (int j = 0; j < kJoints; ++j) EXPECT_NEAR(w->joint_angle_rad(j), rad[j], 1e-9) << j;
    w->reset();
    for (int j = 0; j < kJoints; ++j) EXPECT_NEAR(w->joint_angle_rad(j), 0.0, 1e-12) << j;
  }
}

}  // namespace
}  // namespace curio::app
