// What the controller shares with its callers and its parts: configuration, counters, the
// archived episode's record and the per-cycle probe.
#pragma once
#include <cstdint>

#include "firmware/app/app_status.hpp"
#include "firmware/app/joint_target.hpp"
#include "firmware/explore/config.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/protocol/arm_objects.hpp"

namespace curio::app {

// The control period the drives are told (0x60C2: value 10, index −3, i.e. 10 × 10⁻³ s); a
// paced controller (PeriodPacer) runs its periods on it.
inline constexpr uint8_t kControlPeriodMs = 10;

// What the drives are told at bring-up (drive_config.hpp writes it to every joint and reads it
// back): how they watch the controller and how they stop. Units are the drives' (1 count =
// 1 µrad). The default speed limit is the paper's arm's: π rad per 10 ms period, the largest
// step any exploration commands, so no default result changes; a real arm sets its own
// (--max-joint-speed), and the controller then limits its targets' steps to it too
// (control_cycle.cpp). docs/hil.md, "Objects the controller writes", says why each value.
struct DriveSafetyConfig {
  uint8_t master_node = protocol::od::kDefaultMasterNode;  // its heartbeat: 0x700 + this
  uint16_t master_heartbeat_ms = protocol::od::kDefaultMasterHeartbeatMs;
  uint16_t consumer_time_ms = protocol::od::kDefaultConsumerTimeMs;  // 0x1016, > the period
  int16_t abort_connection_option = protocol::od::kConfigAbortConnection;  // 0x6007
  int16_t quick_stop_option = protocol::od::kConfigQuickStopOption;        // 0x605A
  int16_t fault_reaction_option = protocol::od::kConfigFaultReaction;      // 0x605E
  uint32_t quick_stop_decel = protocol::od::kConfigQuickStopDecelCounts;   // 0x6085, counts/s²
  uint32_t max_speed = protocol::od::kConfigMaxVelocityCounts;  // 0x607F, 0x6080, counts/s
  uint32_t following_error_window = protocol::od::kConfigFollowingErrorWindow;   // 0x6065
  uint16_t following_error_time_ms = protocol::od::kConfigFollowingErrorTimeOutMs;  // 0x6066
};

// A heartbeat the drives can watch: a node id 1..127, a period, and a consumer time above it.
constexpr bool drive_safety_valid(const DriveSafetyConfig& d) {
  return d.master_node >= 1 && d.master_node <= 127 && d.master_heartbeat_ms > 0 &&
         d.consumer_time_ms > d.master_heartbeat_ms && d.quick_stop_decel > 0 && d.max_speed > 0;
}

struct ControllerConfig {
  DriveSafetyConfig drives;
  uint32_t stop_timeout_us = 2'000'000;     // controlled stop: standstill awaited this long
  uint16_t heartbeat_producer_ms = 100;     // written to every node's 0x1017
  uint32_t heartbeat_timeout_us = 350'000;  // consumer: a node is lost after this silence
  uint32_t sdo_timeout_us = 100'000;
  uint32_t boot_timeout_us = 1'000'000;     // boot-up / operational heartbeats after NMT
  uint32_t feedback_timeout_us = 100'000;   // 7 TPDO1 after a SYNC
  uint32_t capture_timeout_us = 1'000'000;  // ground truth + image after a capture request
  // Hold time: after a fault the joints are sent nothing while the arm is brought back (nodes
  // silent, rebooting, bus-off) for at most this long; then the run stops.
  uint32_t recovery_timeout_us = 10'000'000;
  // start_arm() first listens this long without sending: a master already driving the arm
  // (SYNC, NMT, SDO requests) makes it refuse (Fault::kOtherMaster) before it disturbs it.
  uint32_t listen_before_start_us = 300'000;
  uint32_t tx_deadline_us = 50'000;                // every frame we send must reach the bus by then
  int32_t joint_limit_counts = kJointLimitCounts;  // |target| ≤ this (narrower = safer)
  int32_t following_error_counts = 1000;  // |actual − target| (mod 2π) tolerated: 1 mrad
  uint8_t max_attempts = 3;               // per episode (1 = no retry)
  uint8_t capture_attempts = 3;           // per attempt, for capture-only faults
  bool want_image = false;                // capture the camera frame (learned goal spaces)
  bool reset_nodes = true;                // start_arm() begins with NMT reset node (a run from the start)
  // false: no camera node (32) on the bus, a camera on the controller's own computer
  // (frame_source.hpp) instead. The bring-up and the heartbeat consumer skip node 32, no scene
  // reset is sent, and the capture takes the frame from the FrameSource: the first one that
  // arrived frame_settle_us or more after the episode's last period (the arm settled), waiting
  // at most frame_settle_us + frame_timeout_us. No ground truth: learned goal spaces only.
  bool camera_on_bus = true;
  uint32_t frame_settle_us = 250'000;
  uint32_t frame_timeout_us = 3'000'000;
};

struct ControllerCounters {
  uint64_t episodes = 0;  // episodes archived
  uint64_t attempts = 0;  // episode attempts started
  uint64_t replays = 0;   // attempts after a fault (replayed episodes)
  uint64_t capture_retries = 0;
  uint64_t sync_cycles = 0;   // SYNC cycles completed (all feedback in)
  uint64_t arm_bringups = 0;  // start_arm + recoveries
  uint64_t frames_sent = 0;
  uint64_t frames_received = 0;
  uint64_t foreign_frames = 0;       // not for us (other nodes, unknown ids, other masters)
  uint64_t malformed_frames = 0;     // our ids, but not decodable (DLC, format, reserved bits)
  uint64_t unexpected_frames = 0;    // valid, but not now (stale TPDO, duplicate, wrong episode)
  uint64_t bus_errors = 0;           // error frames
  uint64_t emergencies = 0;          // EMCY frames with an error code
  uint64_t node_reboots = 0;         // boot-up heartbeats we did not cause (a node restarted)
  uint64_t other_master_frames = 0;  // NMT, SYNC, RPDO, SDO requests, captures: not ours
  uint64_t duplicate_answers = 0;    // second answers to one SDO request (two nodes, one id)
  uint64_t heartbeats_sent = 0;      // the controller's own heartbeats (not in frames_sent)
  uint64_t limited_targets = 0;      // targets moved to the drives' speed limit (control_cycle)
  uint16_t last_emcy_code = 0;       // the last EMCY with an error code, and its node
  uint8_t last_emcy_node = 0;
  // The configuration write a drive refused or did not keep (drive_config.hpp): node, object,
  // the value written, the value read back, the abort code (0: none, the read-back differed).
  uint8_t config_node = 0;
  uint16_t config_index = 0;
  uint8_t config_sub = 0;
  uint32_t config_written = 0;
  uint32_t config_read = 0;
  uint32_t config_abort = 0;
  // A heartbeat that said operational, then another state (a boot-up included), with no NMT
  // command of ours between: a single node leaves operational only when told to, on an error
  // (CiA 301 error behaviour) or when it restarts; two nodes with one id whose heartbeats
  // interleave do it too (the slower one's heartbeat or boot-up comes after the other's).
  uint64_t state_regressions = 0;
  uint8_t last_regression_node = 0;
  uint64_t faults[kFaultKinds] = {};
  uint64_t fault_total = 0;
  Fault last_fault = Fault::kNone;
  uint8_t last_fault_node = 0;
};

// What one archived episode was (for the host's result files and tests).
struct EpisodeRecord {
  int episode = -1;  // archive index
  EpisodeKind kind = EpisodeKind::kNone;
  int module = -1;        // chosen module (-1: none)
  bool exploit = false;   // kExploit with a module: updated the module's interest
  float progress = 0.0f;  // explorer.last_progress() after an exploit
  float ball[2] = {};     // final ball position (float of the ground truth)
  float distractor[2] = {};
  bool grasped = false;
  int attempts = 0;  // attempts this episode took (1 = no fault)
  int outcome_dim = 0;
  float outcome[kMaxOutcomeDim] = {};
};

// Optional wall-clock pacing of the control periods, as a real arm's cyclic synchronous loop
// runs them: the cycle calls period_begin(t) before it computes step t's targets (the pacer
// blocks until that period's start: t == 0 restarts the schedule there and then, period t starts at
// its start + t·period), and period_end(t) when the step's feedback has been checked. Without
// one the periods follow each other as fast as the arm answers.
class PeriodPacer {
 public:
  virtual void period_begin(int t) = 0;
  virtual void period_end(int t) = 0;

 protected:
  ~PeriodPacer() = default;
};

// Optional per-cycle probe (benchmarks): begin/end bracket each SYNC cycle's own work
// (computing targets, sending, handling the feedback), not the time spent waiting.
class CycleProbe {
 public:
  virtual void cycle_work_begin() = 0;
  virtual void cycle_work_end() = 0;
  virtual void cycle_wait_begin() {}
  virtual void cycle_wait_end() {}

 protected:
  ~CycleProbe() = default;
};

}  // namespace curio::app
