// The controller's CANopen master on one hal::CanBus: frame dispatch, SDO client, NMT and the
// heartbeat consumer, and the attempt's fault.
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/app/app_status.hpp"
#include "firmware/app/controller_types.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "hal/can_bus.hpp"

namespace curio::app {

// Nodes by index: 0..6 the joints, 7 the camera.
inline constexpr int kArmNodes = protocol::kJointNodes + 1;
inline constexpr int kCameraIndex = protocol::kJointNodes;
constexpr uint8_t node_id(int index) {
  return index == kCameraIndex ? protocol::kCameraNode
                               : static_cast<uint8_t>(protocol::kFirstJointNode + index);
}

// What a wait on the master's pump waits for. The frames of one application step (TPDO1
// feedback, ground truth, the camera's ISO-TP frames) go to the step that waits for them;
// a handler that returns false, or a frame that arrives during any other wait, is counted
// unexpected (stale, duplicate, wrong episode).
class Wait {
 public:
  virtual bool done() const = 0;
  // Every wake-up of the pump, before it waits for frames (ISO-TP timers).
  virtual void poll(uint64_t /*now*/) {}
  virtual bool on_feedback(const protocol::JointFeedback& /*fb*/) { return false; }
  virtual bool on_ground_truth(const protocol::GroundTruth& /*g*/) { return false; }
  virtual bool on_camera_frame(const hal::CanFrame& /*f*/, uint64_t /*now*/) { return false; }

 protected:
  ~Wait() = default;
};

class CanOpenMaster {
 public:
  // The controller's configuration and counters, which outlive the master.
  CanOpenMaster(const ControllerConfig* config, ControllerCounters* counters)
      : config_(config), counters_(counters) {}

  void set_bus(hal::CanBus* bus) {
    bus_ = bus;
    ground_truth_.reset();
  }
  hal::CanBus& bus() const { return *bus_; }
  // The arm protocol's profile on this bus (FD or classic frames).
  protocol::CanProfile profile() const { return protocol::profile_for(bus_->carries_fd()); }
  bool bus_off() const;  // bus-off or down: nothing can be sent
  const ControllerConfig& config() const { return *config_; }
  ControllerCounters& counters() const { return *counters_; }
  CycleProbe* probe() const { return probe_; }
  void set_probe(CycleProbe* probe) { probe_ = probe; }
  PeriodPacer* pacer() const { return pacer_; }
  void set_pacer(PeriodPacer* pacer) { pacer_ = pacer; }

  // The fault of the current attempt: the first one raised is its cause; each is counted.
  // A fatal fault (is_fatal: another master or another arm on the bus) is the cause whatever
  // came first, and stays: clear_fault() cannot clear it, so nothing more is attempted.
  void raise(Fault f, uint8_t node);
  Fault fault() const { return fault_; }
  Fault fatal_fault() const { return fatal_; }
  void clear_fault() { fault_ = fatal_; }
  void restore_fault(Fault saved) { fault_ = fatal_ != Fault::kNone ? fatal_ : saved; }

  // Frames of the current attempt (the controller's last_frames_sent/received). Each attempt
  // also re-arms the duplicate-answer check of nodes whose SDO transfer timed out (a late
  // answer to the timed-out request is not a second node).
  void begin_attempt() {
    attempt_frames_sent_ = attempt_frames_received_ = 0;
    for (bool& t : sdo_timed_out_) t = false;
  }
  uint32_t attempt_frames_sent() const { return attempt_frames_sent_; }
  uint32_t attempt_frames_received() const { return attempt_frames_received_; }

  // Sends in one batch within tx_deadline_us; false (fault raised) if the bus refused.
  bool send(const hal::CanFrame* frames, size_t count);
  bool send_nmt(protocol::NmtCommand command);  // to all nodes
  // Receives and dispatches frames until wait.done() or `deadline_us`; false on timeout or
  // a fault (fault() says which).
  bool pump_until(Wait& wait, uint64_t deadline_us);

  // Receives and dispatches for `duration_us` without sending: another master's frames raise
  // kOtherMaster (a fatal fault), so a second controller refuses to start before it sends.
  void listen(uint64_t duration_us);

  // SDO client: one expedited transfer to `node`, or the same one to every joint at once
  // (one batch, then all answers; joint_sdo_value(j) is joint j's answer).
  bool sdo(uint8_t node, protocol::SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
           uint8_t size, uint32_t* read = nullptr);
  bool sdo_all_joints(protocol::SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                      uint8_t size);
  uint32_t joint_sdo_value(int j) const { return sdo_[j].value; }

  // NMT: forget the heartbeats seen so far, then wait until every node has sent one (any
  // state) or every node reports `state`. Boot-up heartbeats are counted as node reboots
  // (counters().node_reboots) except after our own NMT reset (expect_boot_up(true) until the
  // await returns).
  void forget_heartbeats();
  void expect_boot_up(bool expected) { boot_up_expected_ = expected; }
  bool await_nmt(bool any_state, protocol::NmtState state);
  // Heartbeat consumer: from now on a silent node, or one not operational, is a fault.
  void start_heartbeat_watch();
  void stop_heartbeat_watch();

 private:
  class SdoWait;
  class NmtWait;
  static int node_index(uint8_t node);
  void dispatch(const hal::CanFrame& f, uint64_t now, Wait& wait);
  void other_master(uint8_t node);
  bool decoded(protocol::CodecStatus s);
  void on_heartbeat(const protocol::Heartbeat& hb, uint64_t now);
  bool on_sdo_response(const protocol::SdoMessage& m);
  void check_heartbeats(uint64_t now);

  hal::CanBus* bus_ = nullptr;
  const ControllerConfig* config_;
  ControllerCounters* counters_;
  CycleProbe* probe_ = nullptr;
  PeriodPacer* pacer_ = nullptr;
  protocol::GroundTruthAssembler ground_truth_;  // the classic profile's five frames

  Fault fault_ = Fault::kNone;
  Fault fatal_ = Fault::kNone;
  uint32_t attempt_frames_sent_ = 0;
  uint32_t attempt_frames_received_ = 0;

  uint64_t last_heartbeat_us_[kArmNodes] = {};
  protocol::NmtState nmt_state_[kArmNodes] = {};
  bool heard_[kArmNodes] = {};    // a heartbeat/boot-up seen since the last NMT command
  bool operational_since_nmt_[kArmNodes] = {};  // an operational heartbeat since our last NMT
  bool heartbeat_watch_ = false;  // consumer active (after start)
  bool expect_operational_ = false;
  bool boot_up_expected_ = false;  // after our NMT reset node: boot-ups are not reboots

  // Pending SDO transfers (one per node at a time).
  struct SdoPending {
    bool active = false;
    bool done = false;
    bool aborted = false;
    bool upload = false;
    uint16_t index = 0;
    uint8_t sub = 0;
    uint32_t value = 0;
    // m answers this transfer's request: same object, the response kind the request asks for.
    bool is_answer(const protocol::SdoMessage& m) const;
  };
  SdoPending sdo_[kArmNodes];  // stay active after the answer: a second answer is a duplicate
  // Each node's last answered transfer, kept when the master moves on: a second node with the
  // same id that answers late (after our next request went out) is caught by it too.
  SdoPending answered_[kArmNodes];
  void begin_transfers();  // keeps the answered transfers in answered_, clears sdo_
  bool sdo_timed_out_[kArmNodes] = {};  // this attempt: a late answer may still come
  static hal::CanFrame sdo_request(SdoPending& p, uint8_t node, protocol::SdoKind kind,
                                   uint16_t index, uint8_t sub, uint32_t value, uint8_t size);

  static constexpr size_t kRxBatch = 32;
  hal::CanFrame rx_[kRxBatch];
};

}  // namespace curio::app
