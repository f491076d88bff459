// The controller application (issue 5 item 4): the exploration core driving the arm over a
// CAN bus, episode by episode. Firmware: no heap, no exceptions, no OS; it talks to the
// world only through a hal::CanBus (and an optional int8 encoder).
//
//   static curio::Explorer explorer;            // ~3 MB, static storage
//   static curio::app::Controller controller;   // < 20 KB (one camera frame), static storage
//   explorer.init(explorer_config);
//   controller.init(&bus, &explorer, curio::app::ControllerConfig{}, /*encoder=*/nullptr);
//   if (controller.start_arm() != AppStatus::kOk) ...   // NMT reset, SDO config, NMT start, enable
//   while (!explorer.done()) {
//     if (controller.run_episode() != AppStatus::kOk) ...   // retried and still failed
//     const EpisodeRecord& r = controller.last_episode();     // what it archived
//   }
//
// One episode (docs/controller.md has the frame-level sequence):
//   propose θ → SDO camera 0x2000.1 ← episode (scene reset; the same number again = replay)
//   → 50 × { targets a_j(t) → π·a → counts (joint_target.hpp), limit-checked; 7 RPDO1 + SYNC
//   in one batch; collect 7 TPDO1: operation enabled, following error within tolerance }
//   → capture request → ground truth (+ the camera frame over ISO-TP into a static buffer)
//   → outcome: engineered features [distractor x, y, ball x, y] (float of the ground truth)
//   or the encoder's μ of the frame → Explorer::observe.
//
// Faults (docs/controller.md, fault table): any fault ends the attempt at once. Nothing more
// is sent to the joints (they hold the last targets, all of which passed the limit check),
// the fault is counted, the arm is brought up again (fault reset, re-enable; re-init for a
// rebooted node; waiting for bus-off recovery), and the episode is replayed from its start,
// up to max_attempts. Capture faults (ISO-TP errors, timeouts) first retry the capture alone.
// Nothing is archived from an attempt that saw a fault: observe() only ever sees an outcome
// whose 50 cycles and capture all completed without one.
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/app/joint_target.hpp"
#include "firmware/explore/config.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/explore/motor_primitive.hpp"
#include "hal/can_bus.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/cia402.hpp"
#include "firmware/protocol/isotp.hpp"

namespace curio::nn {
class Encoder;
}

namespace curio::app {

enum class AppStatus : uint8_t {
  kOk = 0,
  kNotInitialised,   // init() not called or failed
  kInvalidArgument,  // null bus/explorer, bad config
  kArmNotReady,      // start_arm() did not reach "all joints operation enabled"
  kEpisodeFailed,    // every attempt of the episode hit a fault; nothing archived
  kDone,             // the explorer has observed all its episodes
  kExplorerError,    // propose/observe refused (see explorer counters)
};
const char* to_string(AppStatus s);

enum class Fault : uint8_t {
  kNone = 0,
  kSdoTimeout,          // no SDO answer in time
  kSdoAbort,            // a node refused an SDO transfer
  kBootTimeout,         // a node did not boot / become operational in time
  kHeartbeatLost,       // no heartbeat from a node for heartbeat_timeout_us
  kNodeState,           // a heartbeat reports a node not operational (stopped, rebooted)
  kEmergency,           // an EMCY with an error code
  kDriveFault,          // a statusword not "operation enabled" (fault, disabled, quick stop)
  kFeedbackTimeout,     // not all 7 TPDO1 after a SYNC in time
  kFollowingError,      // actual position differs from the target beyond tolerance
  kJointLimit,          // a computed target outside the joint limits (never sent)
  kBusOff,              // our controller is bus-off or the bus is down
  kSendFailed,          // the bus refused a frame (queue full, deadline)
  kCaptureTimeout,      // ground truth or camera frame incomplete in time
  kImageError,          // ISO-TP: sequence error, truncated, oversized, unexpected
  kGroundTruthInvalid,  // non-finite values
  kEncoderFailed,       // the encoder refused the frame
  kCount
};
inline constexpr size_t kFaultKinds = static_cast<size_t>(Fault::kCount);
const char* to_string(Fault f);

struct ControllerConfig {
  uint16_t heartbeat_producer_ms = 100;     // written to every node's 0x1017
  uint32_t heartbeat_timeout_us = 350'000;  // consumer: a node is lost after this silence
  uint32_t sdo_timeout_us = 100'000;
  uint32_t boot_timeout_us = 1'000'000;            // boot-up / operational heartbeats after NMT
  uint32_t feedback_timeout_us = 100'000;          // 7 TPDO1 after a SYNC
  uint32_t capture_timeout_us = 1'000'000;         // ground truth + image after a capture request
  uint32_t recovery_timeout_us = 2'000'000;        // bringing the arm back after a fault
  uint32_t tx_deadline_us = 50'000;                // every frame we send must reach the bus by then
  int32_t joint_limit_counts = kJointLimitCounts;  // |target| ≤ this (narrower = safer)
  int32_t following_error_counts = 1000;  // |actual − target| (mod 2π) tolerated: 1 mrad
  uint8_t max_attempts = 3;               // per episode (1 = no retry)
  uint8_t capture_attempts = 3;           // per attempt, for capture-only faults
  bool want_image = false;                // capture the camera frame (learned goal spaces)
  bool reset_nodes = true;                // start_arm() begins with NMT reset node (fresh run)
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
  uint64_t foreign_frames = 0;     // not for us (other nodes, unknown ids, other masters)
  uint64_t malformed_frames = 0;   // our ids, but not decodable (DLC, format, reserved bits)
  uint64_t unexpected_frames = 0;  // valid, but not now (stale TPDO, duplicate, wrong episode)
  uint64_t bus_errors = 0;         // error frames
  uint64_t emergencies = 0;        // EMCY frames with an error code
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

class Controller {
 public:
  Controller();

  // Binds the bus, the (initialised) explorer and, for learned goal spaces, the encoder
  // (outcome = μ of the camera frame; want_image is then forced on). No bus traffic yet.
  AppStatus init(hal::CanBus* bus, Explorer* explorer, const ControllerConfig& config,
                 nn::Encoder* encoder = nullptr);

  // NMT reset (optional), boot-up, SDO configuration of all eight nodes, NMT start, CiA 402
  // enable sequence; ends with every joint in "operation enabled".
  AppStatus start_arm();

  // One explorer episode, retried on faults; kOk when it was archived.
  AppStatus run_episode();

  // Reads the simulator physics object (0x2002) of the camera node: 0 kinematic, 1 ODE,
  // 0xFF unknown (a real arm, or no answer). After start_arm().
  uint8_t query_physics();

  // NMT stop to every node: they stop PDO exchange and hold their state.
  void stop_arm();

  const EpisodeRecord& last_episode() const { return record_; }
  const ControllerCounters& counters() const { return counters_; }
  const protocol::IsoTpCounters& image_counters() const { return image_rx_.counters(); }
  const ControllerConfig& config() const { return config_; }
  void set_cycle_probe(CycleProbe* probe) { probe_ = probe; }

  // Frames sent per episode by the last completed attempt (RPDO, SYNC, SDO, capture, FC).
  uint32_t last_frames_sent() const { return attempt_frames_sent_; }
  uint32_t last_frames_received() const { return attempt_frames_received_; }

 private:
  enum class Wait : uint8_t { kSdo, kFeedback, kCapture, kHeartbeats };

  // Bus I/O.
  bool send(const hal::CanFrame* frames, size_t count);
  // Receives and dispatches frames until done(wait) or `deadline_us`; false on timeout or
  // a fault (fault_ says which).
  bool pump_until(Wait wait, uint64_t deadline_us);
  bool wait_done(Wait wait) const;
  void dispatch(const hal::CanFrame& f, uint64_t now);
  void check_heartbeats(uint64_t now);
  void raise(Fault f, uint8_t node);

  // Steps.
  bool sdo(uint8_t node, protocol::SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
           uint8_t size, uint32_t* read = nullptr);
  bool sdo_all_joints(protocol::SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                      uint8_t size);
  bool await_nmt(bool any_state, protocol::NmtState state);
  bool bring_up(bool reset_nodes);
  bool enable_joints();
  bool run_attempt(const float theta[kThetaDim], float* outcome);
  bool run_cycle(int t, const float theta[kThetaDim]);
  bool capture(uint32_t episode, float* outcome);
  bool recover();

  hal::CanBus* bus_ = nullptr;
  Explorer* explorer_ = nullptr;
  nn::Encoder* encoder_ = nullptr;
  ControllerConfig config_;
  MotorPrimitive primitive_;
  CycleProbe* probe_ = nullptr;
  bool initialised_ = false;
  bool arm_ready_ = false;

  // Fault of the current attempt.
  Fault fault_ = Fault::kNone;
  uint8_t fault_node_ = 0;

  // Nodes: 0..6 joints, 7 camera.
  static constexpr int kNodes = protocol::kJointNodes + 1;
  static constexpr int kCameraIndex = protocol::kJointNodes;
  static int node_index(uint8_t node);
  uint64_t last_heartbeat_us_[kNodes] = {};
  protocol::NmtState nmt_state_[kNodes] = {};
  bool heard_[kNodes] = {};       // a heartbeat/boot-up seen since the last NMT command
  bool heartbeat_watch_ = false;  // consumer active (after start)
  bool expect_operational_ = false;
  bool awaited_any_state_ = true;  // Wait::kHeartbeats: any heartbeat, or this state
  protocol::NmtState awaited_state_ = protocol::NmtState::kOperational;

  // Pending SDO transfers (one per node at a time).
  struct SdoPending {
    bool active = false;
    bool done = false;
    bool aborted = false;
    bool upload = false;
    uint16_t index = 0;
    uint8_t sub = 0;
    uint32_t value = 0;
  };
  SdoPending sdo_[kNodes];

  // SYNC cycle.
  int32_t targets_[kJoints] = {};       // targets of the current cycle (all within limits)
  int32_t safe_targets_[kJoints] = {};  // last targets sent: what the joints hold
  bool cycle_active_ = false;
  uint8_t feedback_mask_ = 0;
  protocol::JointFeedback feedback_[kJoints];
  uint8_t sync_counter_ = 0;

  // Capture.
  bool capture_active_ = false;
  uint32_t capture_episode_ = 0;
  bool ground_truth_ok_ = false;
  protocol::GroundTruth ground_truth_;
  bool image_ok_ = false;
  protocol::IsoTpStatus image_status_ = protocol::IsoTpStatus::kIdle;
  uint8_t image_[protocol::kCameraImageBytes] = {};
  protocol::IsoTpReceiver image_rx_;

  static constexpr size_t kRxBatch = 32;
  hal::CanFrame rx_[kRxBatch];

  EpisodeRecord record_;
  ControllerCounters counters_;
  uint32_t attempt_frames_sent_ = 0;
  uint32_t attempt_frames_received_ = 0;
  uint32_t episode_number_ = 0;
  bool episode_started_ = false;  // the camera has seen episode_number_ started
};

}  // namespace curio::app
