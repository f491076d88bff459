// The ODE arm (SPEC §1.3): seven rigid links joined by hinges in the plane, each joint a
// position servo that receives one target per control period. It realises the
// kinematic model with dynamics; the kinematic model is its oracle.
//
// Servo: per control period, a motion step and a settle step (both dWorldStep, exact LCP, not the
// iterative QuickStep). Motion: each hinge's velocity motor runs, with unbounded torque, at the
// speed that reaches its target in one period (feed-forward); the joint angles land on their
// targets (~1e-13 rad). But a rotation of up to π per period integrated to first order throws the
// links' positions off their hinges (measured: hand errors up to 0.16 mid-episode, several units at
// t = 0). Settle: motors hold zero relative speed while joint error correction (ERP 1) closes the
// gaps; with no rotation left this is a pure translation, which the integrator does exactly.
// Measured hand vs the kinematic model: < 1e-13 at every step, at twice the cost of one step per
// period.
// Ball: once grasped it is a kinematic body that follows the hand tip rigidly (a gripper
// that holds it), so it adds no dynamics to the arm and sits exactly on the tip.
// Distractor: a kinematic body placed by the shared random walk. No collisions: the
// reference arm's links pass through each other and through the objects.
#pragma once
#include <ode/common.h>
#include <ode/threading.h>

#include "sim/distractor_walk.hpp"
#include "sim/world.hpp"

namespace curio::sim {

class OdeWorld final : public World {
 public:
  static constexpr double kControlPeriodS = 0.01;  // one target per period
  static constexpr bool kSettleStep = true;

  OdeWorld(const WorldParams& params, uint64_t seed);
  ~OdeWorld() override;
  OdeWorld(const OdeWorld&) = delete;
  OdeWorld& operator=(const OdeWorld&) = delete;

  void reset() override;
  void step(const float commands[kJoints]) override;
  void step_joint_angles(const double angle_rad[kJoints]) override;
  void replay_episode() override;
  void reset_to_episode(uint64_t episode) override;
  const SceneState& state() const override { return scene_; }

  // Relative hinge angle of joint j as the simulated encoder reads it (rad).
  double joint_angle_rad(int j) const override;

  int return_to_start(const double max_step_rad[kJoints]) override;
  void set_joint_speed_limit(double rad_per_s) override { speed_limit_rad_s_ = rad_per_s; }

 private:
  Vec2 hand_tip() const;
  void start_episode();
  // The servo period of step()/step_joint_angles(): targets are hinge angles in rad.
  void servo_step(const double target_rad[kJoints]);
  // The hinges' motion and settle steps of one period toward `target_rad` (no scene update).
  void move_servos(const double target_rad[kJoints]);

  double speed_limit_rad_s_ = 0;  // 0: none

  WorldParams params_;
  DistractorWalk distractor_;
  DistractorWalk episode_start_walk_;  // the walk as the last reset() left it
  SceneState scene_;
  dWorldID world_ = nullptr;
  dThreadingImplementationID threading_ = nullptr;
  dBodyID links_[kJoints] = {};
  dJointID hinges_[kJoints] = {};
  dBodyID ball_ = nullptr;
  dBodyID distractor_body_ = nullptr;
};

}  // namespace curio::sim
