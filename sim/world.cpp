#include "sim/world.hpp"

#include "firmware/app/joint_target.hpp"
#include "firmware/explore/motor_primitive.hpp"
#include "sim/kinematic_world.hpp"
#include "sim/ode_world.hpp"

namespace curio::sim {

bool parse_physics(std::string_view name, Physics* out) {
  if (name == "kinematic") {
    *out = Physics::kKinematic;
    return true;
  }
  if (name == "ode") {
    *out = Physics::kOde;
    return true;
  }
  return false;
}

const char* physics_name(Physics p) {
  switch (p) {
    case Physics::kKinematic:
      return "kinematic";
    case Physics::kOde:
      return "ode";
  }
  return "unknown";
}

SceneState World::rollout(const float theta[kThetaDim]) {
  static const MotorPrimitive primitive;
  reset();
  float commands[kJoints];
  for (int t = 0; t < kStepsPerEpisode; ++t) {
    primitive.commands(theta, t, commands);
    step(commands);
  }
  return state();
}

SceneState World::rollout_joint_targets(const float theta[kThetaDim]) {
  static const MotorPrimitive primitive;
  reset();
  float commands[kJoints];
  double angle_rad[kJoints];
  for (int t = 0; t < kStepsPerEpisode; ++t) {
    primitive.commands(theta, t, commands);
    if (!app::quantized_joint_angles(commands, angle_rad)) {
      // Unreachable for θ from the explorer (commands are clipped); hold the last angles.
      for (int j = 0; j < kJoints; ++j) angle_rad[j] = joint_angle_rad(j);
    }
    step_joint_angles(angle_rad);
  }
  return state();
}

uint64_t world_seed_for_run(uint64_t run_seed) { return run_seed * 0x9E3779B97F4A7C15ULL + 0x5EED; }

std::unique_ptr<World> make_world(Physics physics, const WorldParams& params, uint64_t seed) {
  switch (physics) {
    case Physics::kKinematic:
      return std::make_unique<KinematicWorld>(params, seed);
    case Physics::kOde:
      return std::make_unique<OdeWorld>(params, seed);
  }
  return nullptr;
}

}  // namespace curio::sim
