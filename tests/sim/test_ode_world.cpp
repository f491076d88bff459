// The ODE arm (SPEC §1.3) against its oracle, the kinematic model; thread safety.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "firmware/explore/motor_primitive.hpp"
#include "firmware/explore/prng.hpp"
#include "sim/ode_world.hpp"
#include "sim/scene.hpp"
#include "sim/world.hpp"
#include "tests/sim/scene_equal.hpp"

namespace curio::sim {
namespace {

void random_theta(Prng* rng, float theta[kThetaDim]) {
  for (int i = 0; i < kThetaDim; ++i) theta[i] = static_cast<float>(rng->uniform(-1.0, 1.0));
}

TEST(OdeWorld, StartsAndStaysAtOneZeroForZeroTheta) {
  auto world = make_world(Physics::kOde, {}, 1);
  EXPECT_NEAR(world->state().hand.x, 1.0, 1e-12);
  float theta[kThetaDim] = {};
  const SceneState s = world->rollout(theta);
  EXPECT_NEAR(s.hand.x, 1.0, 1e-9);
  EXPECT_NEAR(s.hand.y, 0.0, 1e-9);
  EXPECT_FALSE(s.grasped);
  EXPECT_EQ(s.ball.x, 0.6);
}

TEST(OdeWorld, ServosReachTheirTargetsEachPeriod) {
  OdeWorld world({}, 1);
  const MotorPrimitive primitive;
  Prng rng(6);
  float theta[kThetaDim];
  float a[kJoints];
  double worst = 0.0;
  for (int e = 0; e < 20; ++e) {
    random_theta(&rng, theta);
    world.reset();
    for (int t = 0; t < kStepsPerEpisode; ++t) {
      primitive.commands(theta, t, a);
      world.step(a);
      for (int j = 0; j < kJoints; ++j) {
        const double err = std::remainder(world.joint_angle_rad(j) - kPi * a[j], 2.0 * kPi);
        worst = std::max(worst, std::fabs(err));
      }
    }
  }
  std::printf("worst joint tracking error: %.3g rad\n", worst);
  EXPECT_LT(worst, 1e-6);
}

// The acceptance criterion of SPEC §1.3: same θ, same grasp decision (≥ 99 %), and the
// same final ball position (< 0.01) when both grasp.
TEST(OdeWorld, AgreesWithKinematicModel) {
  auto kin = make_world(Physics::kKinematic, {}, 2018);
  auto ode = make_world(Physics::kOde, {}, 2018);
  Prng rng(12345);
  float theta[kThetaDim];
  constexpr int kEpisodes = 1000;
  int agree = 0;
  int both_grasp = 0;
  double max_ball_diff = 0.0;
  double max_hand_diff = 0.0;
  for (int e = 0; e < kEpisodes; ++e) {
    random_theta(&rng, theta);
    const SceneState k = kin->rollout(theta);
    const SceneState o = ode->rollout(theta);
    agree += k.grasped == o.grasped;
    max_hand_diff = std::max(max_hand_diff, std::hypot(k.hand.x - o.hand.x, k.hand.y - o.hand.y));
    if (k.grasped && o.grasped) {
      ++both_grasp;
      max_ball_diff = std::max(max_ball_diff, std::hypot(k.ball.x - o.ball.x, k.ball.y - o.ball.y));
    }
  }
  std::printf(
      "ODE vs kinematic on %d random θ: grasp agreement %.2f %% (%d both grasp), "
      "max final ball difference %.3g, max final hand difference %.3g\n",
      kEpisodes, 100.0 * agree / kEpisodes, both_grasp, max_ball_diff, max_hand_diff);
  EXPECT_GE(agree, kEpisodes * 99 / 100);
  EXPECT_GT(both_grasp, 0);
  EXPECT_LT(max_ball_diff, 0.01);
}

TEST(OdeWorld, WorldsInParallelThreadsMatchSequentialRuns) {
  constexpr int kThreads = 4;
  constexpr int kEpisodes = 30;
  auto run = [](uint64_t seed, std::vector<SceneState>* out) {
    auto world = make_world(Physics::kOde, {}, seed);
    Prng rng(seed);
    float theta[kThetaDim];
    for (int e = 0; e < kEpisodes; ++e) {
      random_theta(&rng, theta);
      out->push_back(world->rollout(theta));
    }
  };
  std::vector<std::vector<SceneState>> parallel(kThreads);
  std::vector<std::thread> threads;
  for (int i = 0; i < kThreads; ++i) threads.emplace_back(run, 100 + i, &parallel[i]);
  for (auto& t : threads) t.join();
  for (int i = 0; i < kThreads; ++i) {
    std::vector<SceneState> sequential;
    run(100 + i, &sequential);
    ASSERT_EQ(sequential.size(), parallel[i].size());
    for (int e = 0; e < kEpisodes; ++e) {
      EXPECT_TRUE(identical(sequential[e], parallel[i][e])) << "thread " << i << " episode " << e;
    }
  }
}

TEST(OdeWorld, GraspRadiusAndNoiseAreHonoured) {
  WorldParams params;
  params.grasp_radius = 0.0;  // nothing is strictly closer than 0
  params.distractor_noise = 0.0;
  auto world = make_world(Physics::kOde, params, 3);
  Prng rng(7);
  float theta[kThetaDim];
  for (int e = 0; e < 100; ++e) {
    random_theta(&rng, theta);
    const SceneState s = world->rollout(theta);
    ASSERT_FALSE(s.grasped);
    ASSERT_EQ(s.distractor.x, 0.7);
    ASSERT_EQ(s.distractor.y, -0.45);
  }
}

}  // namespace
}  // namespace curio::sim
