// The identity of a simulated arm's world: everything about it that changes a run's outcomes
// besides the controller's own commands. The camera node publishes it as the manufacturer
// object 0x2003 (arm_objects.hpp), eight u32 words read by expedited SDO, and the controller
// reads it at bring-up and after node reboots and compares it field by field with the world
// the run asked for (host_tools/controller/arm_bring_up.hpp). A real arm has no 0x2003.
//
//   0x2003.0  u8   8 (the highest sub-index)
//   0x2003.1  u32  run seed, bits 0–31          0x2003.2  u32  run seed, bits 32–63
//   0x2003.3  u32  grasp radius, binary64 bits 0–31      0x2003.4  bits 32–63
//   0x2003.5  u32  distractor noise, binary64 bits 0–31  0x2003.6  bits 32–63
//   0x2003.7  u32  renderer version (sim/render.hpp kRendererVersion)
//   0x2003.8  u32  world hash: FNV-1a of physics (0x2002), then words 1–7
//
// The numbers travel as their exact bit patterns: a world is the same world only if every bit
// agrees, as a seed is compared whole (all 64 bits). The hash is a check on the eight reads and
// the short form summary.json and the journal's identity keep (environment hash).
//
// Firmware discipline: no allocation, no floating point (the host converts the bits).
#pragma once
#include <cstdint>

#include "firmware/explore/fnv1a.hpp"

namespace curio::protocol {

struct WorldIdentity {
  uint8_t physics = 0xFF;  // 0x2002: 0 kinematic, 1 ODE
  uint64_t seed = 0;
  uint64_t grasp_radius_bits = 0;
  uint64_t distractor_noise_bits = 0;
  uint32_t renderer_version = 0;
};

inline constexpr uint8_t kWorldIdentityWords = 8;  // 0x2003.1–.8

// Word `sub` (1–7) of the identity; 0 outside.
constexpr uint32_t world_identity_field(const WorldIdentity& w, uint8_t sub) {
  switch (sub) {
    case 1: return static_cast<uint32_t>(w.seed);
    case 2: return static_cast<uint32_t>(w.seed >> 32);
    case 3: return static_cast<uint32_t>(w.grasp_radius_bits);
    case 4: return static_cast<uint32_t>(w.grasp_radius_bits >> 32);
    case 5: return static_cast<uint32_t>(w.distractor_noise_bits);
    case 6: return static_cast<uint32_t>(w.distractor_noise_bits >> 32);
    case 7: return w.renderer_version;
    default: return 0;
  }
}

inline uint32_t world_hash(const WorldIdentity& w) {
  Fnv1a h;
  h.add_u32(w.physics);
  for (uint8_t sub = 1; sub < kWorldIdentityWords; ++sub) h.add_u32(world_identity_field(w, sub));
  return h.h;
}

// Word `sub` (1–8) as the camera node publishes it.
inline uint32_t world_identity_word(const WorldIdentity& w, uint8_t sub) {
  return sub == kWorldIdentityWords ? world_hash(w) : world_identity_field(w, sub);
}

// The identity from words 1–7 as read (words[0] is 0x2003.1) and the physics of 0x2002.
constexpr WorldIdentity world_identity_from_words(const uint32_t (&words)[kWorldIdentityWords - 1],
                                                  uint8_t physics) {
  auto u64 = [&](int lo) { return words[lo] | (static_cast<uint64_t>(words[lo + 1]) << 32); };
  WorldIdentity w;
  w.physics = physics;
  w.seed = u64(0);
  w.grasp_radius_bits = u64(2);
  w.distractor_noise_bits = u64(4);
  w.renderer_version = words[6];
  return w;
}

}  // namespace curio::protocol
