// The ODE arm (SPEC §1.3): seven rigid links joined by hinges in the plane, each joint a
// position servo that receives one target per control period. It realises the
// kinematic model with dynamics; the kinematic model is its oracle.
//
// Servo: per control period the hinge's velocity motor is set to the velocity that
// reaches the target in one period (feed-forward) with unbounded torque, and the world
// advances by dWorldStep (exact LCP; ENGINEERING §6). Ball: once grasped it is a
// kinematic body that follows the hand tip rigidly (a gripper that holds it), so it adds
// no dynamics to the arm. Distractor: a kinematic body placed by the shared random walk.
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
  const SceneState& state() const override { return scene_; }

  // Relative hinge angle of joint j as the simulated encoder reads it (rad).
  double joint_angle_rad(int j) const;

 private:
  Vec2 hand_tip() const;

  WorldParams params_;
  DistractorWalk distractor_;
  SceneState scene_;
  dWorldID world_ = nullptr;
  dThreadingImplementationID threading_ = nullptr;
  dBodyID links_[kJoints] = {};
  dJointID hinges_[kJoints] = {};
  dBodyID ball_ = nullptr;
  dBodyID distractor_body_ = nullptr;
};

}  // namespace curio::sim
