#include "sim/kinematic_world.hpp"

#include "sim/grasp.hpp"
#include "sim/kinematics.hpp"
#include "sim/scene.hpp"

namespace curio::sim {

KinematicWorld::KinematicWorld(const WorldParams& params, uint64_t seed)
    : params_(params),
      distractor_(params.distractor_noise, seed),
      episode_start_walk_(distractor_) {
  reset();
}

void KinematicWorld::reset() {
  distractor_.reset();
  episode_start_walk_ = distractor_;
  start_episode();
}

void KinematicWorld::reset_to_episode(uint64_t episode) {
  distractor_.reset_to_episode(episode);
  episode_start_walk_ = distractor_;
  start_episode();
}

void KinematicWorld::replay_episode() {
  distractor_ = episode_start_walk_;
  start_episode();
}

void KinematicWorld::start_episode() {
  scene_.hand = kHandStart;
  scene_.ball = kBallStart;
  scene_.distractor = distractor_.position();
  scene_.grasped = false;
  for (double& a : joint_angle_rad_) a = 0.0;
}

void KinematicWorld::step(const float commands[kJoints]) {
  scene_.hand = forward_kinematics(commands);
  for (int j = 0; j < kJoints; ++j) joint_angle_rad_[j] = kPi * static_cast<double>(commands[j]);
  finish_step();
}

void KinematicWorld::step_joint_angles(const double angle_rad[kJoints]) {
  scene_.hand = forward_kinematics_angles(angle_rad);
  for (int j = 0; j < kJoints; ++j) joint_angle_rad_[j] = angle_rad[j];
  finish_step();
}

void KinematicWorld::finish_step() {
  apply_grasp_rule(params_.grasp_radius, &scene_);
  distractor_.step();
  scene_.distractor = distractor_.position();
}

}  // namespace curio::sim
