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
//
// CiA 301 identity and communication objects on every node, and the CiA 402 safety objects
// of the joints (the controller writes them at bring-up and reads them back; docs/hil.md
// lists each with the value written and why):
//   all      0x1000.0   u32   ro      device type: joints 0x00020192 (CiA 402 servo drive),
//                                     camera 0x00000000 (a vendor device)
//   all      0x1001.0   u8    ro      error register: bit 0 generic (the drive is in fault or
//                                     its fault reaction), bit 4 communication (a heartbeat
//                                     the node consumes was missed; cleared when it returns)
//   all      0x1016.0   u8    ro      1 (one consumer entry)
//   all      0x1016.1   u32   rw      heartbeat consumer: bits 16–23 producer node, bits 0–15
//                                     consumer time ms; 0 (the power-on value): off. Armed
//                                     by the first heartbeat of the producer after it is
//                                     set; a miss sends EMCY 0x8130 and (joints) reacts as
//                                     0x6007 says
//   all      0x1018.0   u8    ro      4; .1 vendor id, .2 product code, .3 revision number,
//                                     .4 serial number (u32 each; the serial differs per node)
//   joints   0x6007.0   i16   rw      abort connection option: 0 none, 1 fault, 2 disable
//                                     voltage, 3 quick stop (power-on 1)
//   joints   0x605A.0   i16   rw      quick stop option: 0 disable drive, 1/2 slow down on
//                                     the quick stop ramp then switch on disabled, 5/6 the
//                                     same but stay in quick stop active (power-on 2)
//   joints   0x605E.0   i16   rw      fault reaction option: 0 disable drive, 1/2 slow down
//                                     on the quick stop ramp, then fault (power-on 2)
//   joints   0x6065.0   u32   rw      following error window, counts; 0xFFFFFFFF (power-on):
//                                     off
//   joints   0x6066.0   u16   rw      following error time out, ms (power-on 0)
//   joints   0x607D.1/2 i32   rw      software position limits min/max, counts (power-on:
//                                     the joint range ±3141593); a target outside is clamped
//                                     to the limit and reported (EMCY 0x8612 once, counted)
//   joints   0x607F.0   u32   rw      max profile velocity, counts/s (power-on 0xFFFFFFFF);
//   joints   0x6080.0   u32   rw      max motor speed, counts/s (power-on 0xFFFFFFFF): a
//                                     target step beyond the lower of the two per
//                                     interpolation period is limited to it
//   joints   0x6085.0   u32   rw      quick stop deceleration, counts/s² (power-on 10^9)
//   joints   0x6502.0   u32   ro      supported drive modes: 0x00000080 (bit 7: CSP)
//   Any other sub-index of an object that exists aborts with 0x06090011, a value the drive
//   cannot take with 0x06090030, a write to a read-only object with 0x06010002.
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

// EMCY error codes the simulated nodes raise (CiA 301/402 tables).
inline constexpr uint16_t kEmcyHeartbeatLost = 0x8130;   // heartbeat consumer: producer missed
inline constexpr uint16_t kEmcyFollowingError = 0x8611;  // |target − actual| > 0x6065 for 0x6066
inline constexpr uint16_t kEmcyPositionLimit = 0x8612;   // target outside 0x607D (clamped)

// Error register (0x1001) bits.
inline constexpr uint8_t kErrorRegisterGeneric = 0x01;
inline constexpr uint8_t kErrorRegisterCommunication = 0x10;

// ---- CiA 301 identity and heartbeat consumer (every node)
inline constexpr uint16_t kDeviceType = 0x1000;
inline constexpr uint16_t kErrorRegister = 0x1001;
inline constexpr uint16_t kConsumerHeartbeatTime = 0x1016;
inline constexpr uint8_t kConsumerHeartbeatEntries = 1;  // 0x1016.0
inline constexpr uint16_t kIdentity = 0x1018;
inline constexpr uint8_t kIdentityVendorSub = 1;
inline constexpr uint8_t kIdentityProductSub = 2;
inline constexpr uint8_t kIdentityRevisionSub = 3;
inline constexpr uint8_t kIdentitySerialSub = 4;
inline constexpr uint8_t kIdentityEntries = 4;  // 0x1018.0

inline constexpr uint32_t kDeviceTypeServoDrive = 0x00020192;  // CiA 402, servo drive
inline constexpr uint32_t kDeviceTypeCamera = 0x00000000;      // no device profile
// Curio holds no CiA vendor id: 0 ("none assigned"). Product codes and the revision
// (major << 16 | minor) are Curio's own.
inline constexpr uint32_t kVendorId = 0x00000000;
inline constexpr uint32_t kProductCodeJoint = 0x00000402;
inline constexpr uint32_t kProductCodeCamera = 0x00000020;
inline constexpr uint32_t kRevisionNumber = 0x00010000;
// The serial number of node `node`: distinct per node.
constexpr uint32_t serial_number(uint8_t node) { return 0x43520000u | node; }

// 0x1016.1 entry: (producer node << 16) | consumer time ms.
constexpr uint32_t consumer_heartbeat_entry(uint8_t producer, uint16_t time_ms) {
  return (static_cast<uint32_t>(producer) << 16) | time_ms;
}

// ---- The controller's heartbeat (CiA 301 producer on the master), COB-ID 0x700 + node,
// 1 byte NMT state 0x05, every period; the drives consume it with the consumer time.
inline constexpr uint8_t kDefaultMasterNode = 0x7F;
// 100 ms and 500 ms: five periods of margin, so that a host that stalls for a few hundred ms
// under load (measured: a 2,100-episode run on a 2-core machine with ten compile jobs missed
// one 200 ms window) does not stop the arm, while a dead controller stops it within 0.6 s.
inline constexpr uint16_t kDefaultMasterHeartbeatMs = 100;
inline constexpr uint16_t kDefaultConsumerTimeMs = 500;

// ---- CiA 402 safety objects (joints)
inline constexpr uint16_t kAbortConnectionOption = 0x6007;
inline constexpr uint16_t kQuickStopOptionCode = 0x605A;
inline constexpr uint16_t kFaultReactionOptionCode = 0x605E;
inline constexpr uint16_t kFollowingErrorWindow = 0x6065;
inline constexpr uint16_t kFollowingErrorTimeOut = 0x6066;
inline constexpr uint16_t kSoftwarePositionLimit = 0x607D;
inline constexpr uint8_t kPositionLimitMinSub = 1;
inline constexpr uint8_t kPositionLimitMaxSub = 2;
inline constexpr uint16_t kMaxProfileVelocity = 0x607F;
inline constexpr uint16_t kMaxMotorSpeed = 0x6080;
inline constexpr uint16_t kQuickStopDeceleration = 0x6085;
inline constexpr uint16_t kSupportedDriveModes = 0x6502;
inline constexpr uint32_t kSupportedDriveModesCsp = 0x00000080;  // bit 7: CSP

// 0x6007 values.
inline constexpr int16_t kAbortConnectionNone = 0;
inline constexpr int16_t kAbortConnectionFault = 1;
inline constexpr int16_t kAbortConnectionDisableVoltage = 2;
inline constexpr int16_t kAbortConnectionQuickStop = 3;
// 0x605A values the joints support (CiA 402: 0 disable drive; 1 slow down ramp, 2 quick stop
// ramp, then switch on disabled; 5, 6 the same, then stay in quick stop active). Curio's
// drives have one deceleration, 0x6085, for the slow down and the quick stop ramp.
inline constexpr int16_t kQuickStopDisableDrive = 0;
inline constexpr int16_t kQuickStopSlowDownRamp = 1;
inline constexpr int16_t kQuickStopRampThenDisabled = 2;
inline constexpr int16_t kQuickStopSlowDownRampStay = 5;
inline constexpr int16_t kQuickStopRampStay = 6;
// 0x605E values (0 disable drive, 1 slow down ramp, 2 quick stop ramp; then fault).
inline constexpr int16_t kFaultReactionDisableDrive = 0;
inline constexpr int16_t kFaultReactionSlowDownRamp = 1;
inline constexpr int16_t kFaultReactionQuickStopRamp = 2;
// 0x6065 value that switches the following error check off (CiA 402).
inline constexpr uint32_t kFollowingErrorOff = 0xFFFFFFFF;

// Power-on values of the joints (CiA 402 defaults where it gives one): with them the
// joints behave as before any configuration (no consumer, no limit beyond the joint range).
inline constexpr int16_t kPowerOnAbortConnection = kAbortConnectionFault;
inline constexpr int16_t kPowerOnQuickStopOption = kQuickStopRampThenDisabled;
inline constexpr int16_t kPowerOnFaultReaction = kFaultReactionQuickStopRamp;
inline constexpr uint32_t kPowerOnQuickStopDecelCounts = 1'000'000'000;  // 1000 rad/s²
inline constexpr uint32_t kPowerOnMaxVelocityCounts = 0xFFFFFFFF;         // no limit
inline constexpr uint32_t kPowerOnFollowingErrorWindow = kFollowingErrorOff;
inline constexpr uint16_t kPowerOnFollowingErrorTimeOutMs = 0;

// The values Curio's controller writes at bring-up (docs/hil.md says why):
//   quick stop on a lost controller, then switch on disabled; faults on the same ramp;
//   1000 rad/s² deceleration (10^9 counts/s²);
//   the speed limit: π rad per 10 ms period (314,159,300 counts/s). The motor primitive's
//   commands are clipped to [−1, 1] (angle π·a) and start from the rest pose, so the first
//   step of an episode can be a whole π and no step is larger: with this limit no target of
//   any exploration is ever limited and every result stays as it was (a real arm is far
//   slower; docs/hil.md);
//   following error: 0.05 rad for 20 ms (the ODE servo lands on each target to ~1e-13 rad).
inline constexpr int16_t kConfigAbortConnection = kAbortConnectionQuickStop;
inline constexpr int16_t kConfigQuickStopOption = kQuickStopRampThenDisabled;
inline constexpr int16_t kConfigFaultReaction = kFaultReactionQuickStopRamp;
inline constexpr uint32_t kConfigQuickStopDecelCounts = 1'000'000'000;
inline constexpr uint32_t kConfigMaxVelocityCounts = 314'159'300;
inline constexpr uint32_t kConfigFollowingErrorWindow = 50'000;
inline constexpr uint16_t kConfigFollowingErrorTimeOutMs = 20;

}  // namespace curio::protocol::od
