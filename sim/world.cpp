#include "sim/world.hpp"

#include "explore/motor_primitive.hpp"
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
