// The kinematic reference model (SPEC §1.1): the pose follows each command at once.
// The paper's environment, the oracle for the ODE arm, and the fast mode.
#pragma once
#include "sim/distractor_walk.hpp"
#include "sim/world.hpp"

namespace curio::sim {

class KinematicWorld final : public World {
 public:
  KinematicWorld(const WorldParams& params, uint64_t seed);

  void reset() override;
  void step(const float commands[kJoints]) override;
  void step_joint_angles(const double angle_rad[kJoints]) override;
  double joint_angle_rad(int j) const override { return joint_angle_rad_[j]; }
  void replay_episode() override;
  void reset_to_episode(uint64_t episode) override;
  const SceneState& state() const override { return scene_; }

 private:
  void start_episode();
  void finish_step();

  WorldParams params_;
  DistractorWalk distractor_;
  DistractorWalk episode_start_walk_;  // the walk as the last reset() left it
  SceneState scene_;
  double joint_angle_rad_[kJoints] = {};
};

}  // namespace curio::sim
