// The controller application: the exploration core driving the arm over a
// CAN bus, episode by episode. Firmware: no heap, no exceptions, no OS; it talks to the
// world only through a hal::CanBus (and an optional int8 encoder).
//
//   static curio::Explorer explorer;            // ~3 MB, static storage
//   static curio::app::Controller controller;   // < 20 KB (one camera frame), static storage
//   explorer.init(explorer_config);
//   controller.init(&bus, &explorer, curio::app::ControllerConfig{}, /*encoder=*/nullptr);
//   if (controller.start_arm() != AppStatus::kOk) ...   // NMT reset, identity, SDO config, NMT start, enable
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
// Safety (docs/hil.md): the controller produces its heartbeat (heartbeat_producer.hpp) and
// configures every drive to watch it and to stop on a quick-stop ramp when it misses it
// (drive_config.hpp); every end of a run is a controlled stop (controlled_stop.hpp).
//
// Faults (docs/controller.md, fault table): any fault ends the attempt at once. Nothing more
// is sent to the joints (they hold the last targets, all of which passed the limit check),
// the fault is counted, the arm is brought up again (fault reset, re-enable; re-init for a
// rebooted node; waiting for bus-off recovery), and the episode is replayed from its start,
// up to max_attempts. Capture faults (ISO-TP errors, timeouts) first retry the capture alone.
// Nothing is archived from an attempt that saw a fault: observe() only ever sees an outcome
// whose 50 cycles and capture all completed without one.
//
// The parts (one job each, composed here): canopen_master (dispatch, SDO client, NMT,
// heartbeat consumer, the attempt's fault), arm_bringup (start-up, enable, recovery),
// control_cycle (one SYNC cycle), episode_capture + episode_outcome (capture and outcome),
// episode_attempts (capture retries, replays); app_status and controller_types hold the
// vocabulary below.
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/app/app_status.hpp"
#include "firmware/app/canopen_master.hpp"
#include "firmware/app/control_cycle.hpp"
#include "firmware/app/controlled_stop.hpp"
#include "firmware/app/controller_types.hpp"
#include "firmware/app/episode_attempts.hpp"
#include "firmware/app/episode_capture.hpp"
#include "firmware/app/joint_target.hpp"
#include "firmware/app/node_identity.hpp"
#include "firmware/explore/config.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/explore/motor_primitive.hpp"
#include "firmware/journal/journal.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/cia402.hpp"
#include "firmware/protocol/isotp.hpp"
#include "hal/can_bus.hpp"

namespace curio::nn {
class Encoder;
}

namespace curio::app {

class Controller {
 public:
  Controller();
  Controller(const Controller&) = delete;  // its parts point at each other
  Controller& operator=(const Controller&) = delete;

  // Binds the bus, the (initialised) explorer and, for learned goal spaces, the encoder
  // (outcome = μ of the camera frame; want_image is then forced on). No bus traffic yet.
  AppStatus init(hal::CanBus* bus, Explorer* explorer, const ControllerConfig& config,
                 nn::Encoder* encoder = nullptr);

  // Listens first (listen_before_start_us: another master's frames make it refuse, fatal
  // kOtherMaster, having sent nothing), then NMT reset (optional), boot-up, SDO configuration
  // of all eight nodes, NMT start, CiA 402 enable sequence; ends with every joint in
  // "operation enabled".
  AppStatus start_arm();

  // One explorer episode, retried on faults; kOk when it was archived.
  AppStatus run_episode();

  // Reads the simulator physics object (0x2002) of the camera node: 0 kinematic, 1 ODE,
  // 0xFF unknown (a real arm, or no answer). After start_arm().
  uint8_t query_physics();

  // Reads one object of the camera node by SDO (after start_arm), e.g. 0x2000.2 (episode-
  // indexed scenes) or 0x2003 (run seed): false when it does not answer or refuses ("object
  // does not exist" on a real arm). The attempt's fault is left as it was.
  bool read_camera_object(uint16_t index, uint8_t sub, uint32_t* value);

  // Another master or another arm seen on the bus (is_fatal): kNone, or why the run stopped.
  Fault fatal_fault() const { return master_.fatal_fault(); }

  // The controlled stop (controlled_stop.hpp): quick stop to every joint, standstill awaited
  // (bounded by stop_timeout_us), disable voltage, the drives' heartbeat consumer off, NMT
  // stop; nothing on a bus that is off or shared with another master or arm. Every end of a
  // run calls it; the report says what the joints confirmed.
  StopReport stop_arm();

  // A stop request: while *flag is non-zero the running wait ends within 10 ms with
  // Fault::kStopRequested (no replay, no recovery); the caller then calls stop_arm(). The
  // host's SIGTERM/SIGINT/SIGHUP handler sets it.
  void set_stop_request(const volatile int* flag) { master_.set_stop_request(flag); }

  // Every node's CiA 301 identity (0x1000, 0x1018), read by start_arm(); by node index (0..6
  // the joints, 7 the camera).
  const NodeIdentity& identity(int index) const { return identity_[index]; }

  // Optional journal (firmware/journal/journal.hpp, created or resumed by the caller): every
  // archived episode is appended right after Explorer::observe(); a failed append returns
  // kJournalError (the episode is in the archive but would be run again on a resume).
  void set_journal(journal::JournalWriter* journal) { journal_ = journal; }

  // The camera on the controller's computer, for config.camera_on_bus false (frame_source.hpp);
  // set before the first episode.
  void set_frame_source(FrameSource* source) { capture_.set_frame_source(source); }

  const EpisodeRecord& last_episode() const { return record_; }
  const ControllerCounters& counters() const { return counters_; }
  const protocol::IsoTpCounters& image_counters() const { return capture_.image_counters(); }
  const ControllerConfig& config() const { return config_; }
  void set_cycle_probe(CycleProbe* probe) { master_.set_probe(probe); }
  // Optional wall-clock pacing of the control periods (controller_types.hpp); nullptr: none.
  void set_period_pacer(PeriodPacer* pacer) { master_.set_pacer(pacer); }

  // Frames sent per episode by the last completed attempt (RPDO, SYNC, SDO, capture, FC).
  uint32_t last_frames_sent() const { return master_.attempt_frames_sent(); }
  uint32_t last_frames_received() const { return master_.attempt_frames_received(); }

 private:
  Explorer* explorer_ = nullptr;
  nn::Encoder* encoder_ = nullptr;
  journal::JournalWriter* journal_ = nullptr;
  ControllerConfig config_;
  ControllerCounters counters_;
  bool initialised_ = false;
  bool arm_ready_ = false;

  CanOpenMaster master_;
  ControlCycle cycle_;
  EpisodeCapture capture_;
  EpisodeAttempts attempts_;

  EpisodeRecord record_;
  NodeIdentity identity_[kArmNodes];
};

}  // namespace curio::app
