#include "sim/kinematic_world.hpp"

#include "sim/grasp.hpp"
#include "sim/kinematics.hpp"
#include "sim/scene.hpp"

namespace curio::sim {

KinematicWorld::KinematicWorld(const WorldParams& params, uint64_t seed)
    : params_(params), distractor_(params.distractor_noise, seed) {
  reset();
}

void KinematicWorld::reset() {
  distractor_.reset();
  scene_.hand = kHandStart;
  scene_.ball = kBallStart;
  scene_.distractor = distractor_.position();
  scene_.grasped = false;
}

void KinematicWorld::step(const float commands[kJoints]) {
  scene_.hand = forward_kinematics(commands);
  apply_grasp_rule(params_.grasp_radius, &scene_);
  distractor_.step();
  scene_.distractor = distractor_.position();
}

}  // namespace curio::sim
