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
  const SceneState& state() const override { return scene_; }

 private:
  WorldParams params_;
  DistractorWalk distractor_;
  SceneState scene_;
};

}  // namespace curio::sim
