// The object dictionary entries Curio's controller writes and reads by SDO (expedited), and
// the simulated arm (sim/serve) implements. Standard CiA 301/402 objects plus three
// manufacturer-specific objects of the camera node (0x2000–0x2FFF is the manufacturer area):
//
//   node     index.sub  type  access  meaning
//   all      0x1017.0   u16   rw      heartbeat producer time, ms (0 = off)
//   joints   0x6040.0   u16   rw      controlword (CiA 402 state machine, applied at once)
//   joints   0x6041.0   u16   ro      statusword
//   joints   0x6060.0   i8    rw      modes of operation: only 8 (cyclic synchronous position)
//   joints   0x6061.0   i8    ro      modes of operation display
//   joints   0x6064.0   i32   ro      position actual value, counts (1 count = 1 µrad)
//   joints   0x607A.0   i32   rw      target position, counts (also RPDO1)
//   joints   0x60C2.1   u8    rw      interpolation time period value
//   joints   0x60C2.2   i8    rw      interpolation time period index (10^x s)
//   camera   0x2000.1   u32   wo      EPISODE START: the scene goes to the episode's start
//                                     state (arm at zeros, ball (0.6,0.6), distractor
//                                     (0.7,−0.45)); value = episode number. Writing the same
//                                     number as the previous start replays that episode:
//                                     the distractor's random stream is rewound to where it
//                                     was at that start (so a retried episode is identical).
//                                     The download response comes after the reset is done.
//                                     The controller writes the archive index of the episode
//                                     (0, 1, 2, ... in order; the same again for a replay).
//   camera   0x2000.2   u8    ro      EPISODE-INDEXED SCENES: 1 = the scene's randomness is
//                                     a function of (run seed, episode number) alone (the
//                                     simulator positions its distractor stream at episode
//                                     n), so a replay, or an episode after the node
//                                     restarted, runs exactly as in an undisturbed run;
//                                     0 = not guaranteed (a real arm)
//   camera   0x2001.0   u8    rw      capture content: bit 0 camera image (ISO-TP),
//                                     bit 1 ground-truth message; default 0x03
//   camera   0x2002.0   u8    ro      simulator physics: 0 kinematic, 1 ODE, 0xFF real arm
//   camera   0x2003.0   u8    ro      WORLD IDENTITY of the simulated world (world_identity.hpp):
//            0x2003.1–8 u32   ro      .1/.2 run seed (all 64 bits), .3/.4 grasp radius, .5/.6
//                                     distractor noise (binary64 bits), .7 renderer version,
//                                     .8 world hash; "object does not exist" on a real arm
//
// Episode protocol (docs/controller.md): SDO 0x2000.1 ← n; 50 × (7 RPDO1 + SYNC → world
// steps once → 7 TPDO1); capture request 0x220 (episode n) → ground truth 0x2A0 and the
// image over ISO-TP.
#pragma once
#include <cstdint>

namespace curio::protocol::od {

inline constexpr uint16_t kHeartbeatProducerTime = 0x1017;
inline constexpr uint16_t kEpisodeControl = 0x2000;
inline constexpr uint8_t kEpisodeStartSub = 1;
inline constexpr uint8_t kEpisodeIndexedSub = 2;
inline constexpr uint16_t kCaptureContent = 0x2001;
inline constexpr uint8_t kCaptureImage = 0x01;
inline constexpr uint8_t kCaptureGroundTruth = 0x02;
inline constexpr uint16_t kSimulatorPhysics = 0x2002;
inline constexpr uint8_t kPhysicsKinematic = 0;
inline constexpr uint8_t kPhysicsOde = 1;
inline constexpr uint8_t kPhysicsRealArm = 0xFF;
inline constexpr uint16_t kWorldIdentity = 0x2003;
inline constexpr uint8_t kInterpolationPeriodValueSub = 1;
inline constexpr uint8_t kInterpolationPeriodIndexSub = 2;

// EMCY error codes the simulated joints raise (CiA 402 table).
inline constexpr uint16_t kEmcyFollowingError = 0x8611;
inline constexpr uint16_t kEmcyPositionLimit = 0x8612;  // target outside the joint's range

}  // namespace curio::protocol::od
