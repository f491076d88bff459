// The simulated arm as CAN nodes: seven CiA 402 joint drives (node ids 1–7,
// cyclic synchronous position mode) and the camera node (0x20), in lockstep with the world:
// the world advances one control period per SYNC while an episode runs.
//
// Joints: boot-up heartbeat, NMT (start/stop/pre-operational/reset), expedited SDO server
// (objects in firmware/protocol/arm_objects.hpp), the CiA 402 state machine driven by the
// controlword (SDO 0x6040 or RPDO1; applied at once), RPDO1 target latched and applied at the
// next SYNC, TPDO1 (statusword, actual position) after each SYNC, heartbeats every 0x1017 ms,
// the CiA 301 identity and the CiA 402 safety objects, enforced (firmware/protocol/
// joint_node.hpp): targets clamped to 0x607D (EMCY 0x8612 once), steps limited to
// 0x607F/0x6080, following error (0x6065/0x6066: EMCY 0x8611 and the fault reaction), the
// controller's heartbeat consumed (0x1016: EMCY 0x8130 and the 0x6007 reaction). A joint in
// quick stop or fault reaction decelerates on 0x6085 to standstill in the drive's own time:
// the world steps once per interpolation period of the serve's wall clock while a joint
// ramps, SYNC or not (a dead controller sends none). Each joint's missed heartbeat and
// standstill are logged (ServeOptions::log). Between episodes the ODE arm returns to its start
// pose within each joint's speed limit (World::return_to_start).
// Camera: SDO 0x2000.1 starts (or replays) episode n, its world positioned by (seed, n)
// (World::reset_to_episode; 0x2000.2 reads 1, 0x2003 the world's identity); a capture request for
// the current episode renders the final scene (sim/render.hpp → sim/camera.hpp) and sends the
// ground-truth message and the 64×64×3 frame over ISO-TP (CAN FD), as 0x2001 selects.
// A joint that is not operation-enabled holds its angle when the world steps.
//
// The nodes' protocol side is firmware/protocol/arm_node_set.hpp (shared with the Cortex-M7
// controller image's fake arm, tests/app/qemu_app/fake_arm.hpp); this class adds the world,
// the camera image and the bus.
//
// Single-threaded: one thread calls poll()/run(); the bus may be shared with other threads
// (loopback) or processes (UDP, SocketCAN).
#pragma once
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <memory>

#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/arm_node_set.hpp"
#include "firmware/protocol/cia402.hpp"
#include "hal/can_bus.hpp"
#include "sim/camera.hpp"
#include "sim/serve/sync_timing.hpp"
#include "sim/world.hpp"

namespace curio::sim::serve {

struct ServeOptions {
  Physics physics = Physics::kOde;
  WorldParams world;
  uint64_t seed = 0;  // run seed: the world is seeded with world_seed_for_run(seed)
  // > 0: the drives' control period in µs; the SYNC intervals of each episode are measured
  // against it (sync_timing()). The world still steps once per SYNC.
  uint64_t period_us = 0;
  // Where the joints' safety events go, one line each (nullptr: nowhere).
  std::FILE* log = nullptr;
  // > 0: the joints' motor speed limit in rad/s (World::set_joint_speed_limit; fault
  // injection: the ODE joints lag behind fast targets).
  double joint_speed_limit_rad_s = 0;
  // false: node 0x20 is not on the bus (a camera on the controller's computer instead: the
  // serve streams its scene, camera_stream.hpp). The camera node then sends and answers
  // nothing, and the episodes start themselves: episode n (n = 0, 1, ... since the start or an
  // NMT reset) at the first SYNC after episode n − 1's 50 steps. An NMT command after an
  // episode started (the controller's recovery, which replays it: a fault in its periods or
  // while the controller waited for its frame) makes the next SYNC start that episode again.
  // After a controller's --resume the scenes follow this count, not the journal's (the
  // controller cannot name the episode to a node that is not there).
  bool camera_node = true;
};

struct ServeCounters {
  uint64_t frames_in = 0;
  uint64_t frames_out = 0;
  uint64_t tx_failures = 0;  // frames the bus refused
  uint64_t syncs = 0;
  uint64_t steps = 0;           // world steps (SYNCs inside an episode)
  uint64_t idle_syncs = 0;      // SYNCs outside an episode or after its 50 steps
  uint64_t episodes = 0;        // episode starts (0x2000.1 writes)
  uint64_t replays = 0;         // of which replays of the previous episode
  uint64_t captures = 0;        // capture requests served
  uint64_t stale_captures = 0;  // capture requests for another episode (ignored)
  uint64_t images_sent = 0;     // ISO-TP transfers completed
  uint64_t image_errors = 0;    // ISO-TP transfers that failed (flow control, timeout)
  uint64_t sdo_requests = 0;
  uint64_t sdo_aborts = 0;         // requests answered with an abort
  uint64_t rejected_targets = 0;   // targets outside 0x607D (clamped to the limit)
  uint64_t limited_targets = 0;    // target steps beyond 0x607F/0x6080 (limited)
  uint64_t heartbeats_missed = 0;  // consumer misses (0x1016), all nodes
  uint64_t following_errors = 0;
  uint64_t ramp_steps = 0;    // world steps on the serve's own clock (quick stop, fault)
  uint64_t return_steps = 0;  // control periods of the ODE arm's returns to its start pose
  uint64_t emcy_sent = 0;
  uint64_t heartbeats_sent = 0;
  uint64_t foreign = 0;    // frames for nobody here (other nodes, other ids)
  uint64_t malformed = 0;  // frames with our ids that do not decode
};

class ArmNodes {
 public:
  // `bus` must outlive this object. Sends the boot-up heartbeats of all eight nodes.
  ArmNodes(hal::CanBus* bus, const ServeOptions& options);
  ~ArmNodes();
  ArmNodes(const ArmNodes&) = delete;
  ArmNodes& operator=(const ArmNodes&) = delete;

  // Waits up to `timeout_us` for frames (less if a heartbeat or image frame is due), handles
  // every frame received and sends what is due. Returns the bus status of the receive
  // (kOk, kTimeout) or a hard error (kIoError, kBusOff, ...).
  hal::CanStatus poll(uint64_t timeout_us);

  // poll() until `stop` is set (checked at least every 50 ms).
  void run(const std::atomic<bool>& stop);

  const ServeCounters& counters() const { return counters_; }
  // The SYNC intervals inside episodes against options.period_us (empty when it is 0).
  SyncTiming::Summary sync_timing() const { return sync_timing_.summary(); }
  const World& world() const { return *world_; }
  // Episodes started so far and whether the current one has run its 50 steps (no camera node:
  // the camera stream and the positions file follow them).
  uint32_t episode() const { return nodes_.camera.episode; }
  bool episode_done() const {
    return nodes_.camera.episode_started && nodes_.camera.steps >= kStepsPerEpisode;
  }
  protocol::cia402::DriveState drive_state(int joint) const {
    return nodes_.joints[joint].drive.state;
  }
  const protocol::JointNode& joint(int j) const { return nodes_.joints[j]; }

  // A joint's safety events on the serve's clock (bus now_us), 0: none yet.
  struct JointEvents {
    uint64_t missed_us = 0;      // the consumed heartbeat was missed (last time)
    uint64_t ramp_from_us = 0;   // quick stop or fault reaction began (last time)
    uint64_t standstill_us = 0;  // its ramp reached standstill (last time)
    double standstill_rad = 0;   // where
  };
  const JointEvents& joint_events(int j) const { return events_[j]; }

 private:
  // The nodes send into the batch, count into counters_ and read the bus's clock.
  class Io final : public protocol::NodeIo {
   public:
    explicit Io(ArmNodes* nodes) : nodes_(nodes) {}
    void send(const hal::CanFrame& f) override { nodes_->queue(f); }
    void count(Event e) override;
    uint64_t now_us() override { return nodes_->bus_->now_us(); }

   private:
    ArmNodes* nodes_;
  };

  void handle(const hal::CanFrame& f);
  void on_nmt(const protocol::NmtMessage& m);
  void on_sync();
  void on_sdo(const protocol::SdoMessage& m);
  void on_capture(const protocol::CameraCapture& c);
  void actual_counts(int32_t counts[protocol::kJointNodes]) const;  // position actual values
  void pump_image(uint64_t now);
  // The consumers' checks and heartbeats due; logs the joints' misses and ramp starts.
  void timers_due(uint64_t now);
  // The ramp clock: one world step per interpolation period while a joint ramps.
  void ramp_due(uint64_t now);
  void note_ramp_starts(uint64_t now);
  void after_world_step();
  void return_to_start();
  void queue(const hal::CanFrame& f);
  void flush();
  uint64_t next_due_us(uint64_t now) const;

  hal::CanBus* bus_;
  ServeOptions options_;
  std::unique_ptr<World> world_;
  Io io_{this};
  protocol::ArmNodeSet nodes_;
  std::unique_ptr<Image> image_;
  std::unique_ptr<CameraFrame> frame_;
  protocol::IsoTpSender image_sender_;
  static constexpr size_t kBatch = 64;
  hal::CanFrame rx_[kBatch];
  hal::CanFrame tx_[kBatch];
  size_t tx_count_ = 0;
  ServeCounters counters_;
  SyncTiming sync_timing_;
  JointEvents events_[protocol::kJointNodes];
  bool was_ramping_[protocol::kJointNodes] = {};
  uint64_t next_ramp_us_ = 0;  // 0: the ramp clock is not running
  uint32_t next_episode_ = 0;  // no camera node: the episode the next start begins
  uint64_t start_us_;          // the bus clock when the nodes powered on (log times)
};

}  // namespace curio::sim::serve
