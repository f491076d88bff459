// The simulated world's identity (firmware/protocol/world_identity.hpp) from what decides it:
// the physics, the world parameters, the run seed and the renderer's version. `curio-sim serve`
// publishes it (camera 0x2003); curio-controller builds the one its run asks for and compares
// (host_tools/controller/arm_bring_up.hpp), naming the first field that differs.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>

#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/world_identity.hpp"
#include "sim/render.hpp"
#include "sim/world.hpp"

namespace curio::sim {

inline uint64_t double_bits(double v) {
  uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

inline double bits_double(uint64_t bits) {
  double v = 0.0;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

inline protocol::WorldIdentity world_identity(Physics physics, const WorldParams& world,
                                              uint64_t seed) {
  protocol::WorldIdentity w;
  w.physics = physics == Physics::kOde ? protocol::od::kPhysicsOde : protocol::od::kPhysicsKinematic;
  w.seed = seed;
  w.grasp_radius_bits = double_bits(world.grasp_radius);
  w.distractor_noise_bits = double_bits(world.distractor_noise);
  w.renderer_version = kRendererVersion;
  return w;
}

}  // namespace curio::sim
