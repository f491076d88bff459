// The controller's CANopen master on one hal::CanBus: a thin dispatcher over its services, one
// per file as in CANopenNode: the SDO client (sdo_client.hpp), NMT (nmt_master.hpp), the
// heartbeat consumer (heartbeat_consumer.hpp) and producer (heartbeat_producer.hpp), the EMCY
// consumer (emcy_consumer.hpp), the SYNC producer (sync_producer.hpp, whose frame goes out with
// each control period's targets from control_cycle.cpp). The arm's own frames (feedback, ground
// truth, camera) go to the Wait of the step that waits for them (the control cycle, the capture).
// The master also holds the attempt's fault: the first one raised is its cause.
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/app/app_status.hpp"
#include "firmware/app/controller_types.hpp"
#include "firmware/app/emcy_consumer.hpp"
#include "firmware/app/heartbeat_consumer.hpp"
#include "firmware/app/heartbeat_producer.hpp"
#include "firmware/app/nmt_master.hpp"
#include "firmware/app/sdo_client.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "hal/can_bus.hpp"

namespace curio::app {

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
  CanOpenMaster(const CanOpenMaster&) = delete;  // its services point back at it
  CanOpenMaster& operator=(const CanOpenMaster&) = delete;

  void set_bus(hal::CanBus* bus) {
    bus_ = bus;
    ground_truth_.reset();
  }
  hal::CanBus& bus() const { return *bus_; }
  // The arm protocol's profile on this bus (FD or classic frames).
  protocol::CanProfile profile() const { return protocol::profile_for(bus_->carries_fd()); }
  bool bus_off() const;  // bus-off or down: nothing can be sent
  const ControllerConfig& config() const { return *config_; }
  // Node index i is on this bus: every joint, and the camera unless a camera on the
  // controller's computer replaces it (ControllerConfig::camera_on_bus).
  bool node_on_bus(int i) const { return i != kCameraIndex || config_->camera_on_bus; }
  ControllerCounters& counters() const { return *counters_; }
  CycleProbe* probe() const { return probe_; }
  void set_probe(CycleProbe* probe) { probe_ = probe; }
  PeriodPacer* pacer() const { return pacer_; }
  void set_pacer(PeriodPacer* pacer) { pacer_ = pacer; }

  // A stop request (the host's signal handler sets *flag non-zero): the pump raises
  // kStopRequested at its next wake-up (within 10 ms), so the attempt ends at once and the
  // controller stops the arm in a controlled way (controlled_stop.hpp).
  void set_stop_request(const volatile int* flag) { stop_request_ = flag; }
  bool stop_requested() const { return stop_request_ != nullptr && *stop_request_ != 0; }

  // The fault of the current attempt: the first one raised is its cause; each is counted.
  // A fatal fault (is_fatal: another master or another arm on the bus) is the cause whatever
  // came first, and stays: clear_fault() cannot clear it, so nothing more is attempted.
  // While stopping (set_stopping), faults are counted but set no cause: the controlled stop
  // goes on through them.
  void raise(Fault f, uint8_t node);
  Fault fault() const { return fault_; }
  Fault fatal_fault() const { return fatal_; }
  void clear_fault() { fault_ = fatal_; }
  void restore_fault(Fault saved) { fault_ = fatal_ != Fault::kNone ? fatal_ : saved; }
  void set_stopping(bool stopping) { stopping_ = stopping; }

  // Frames of the current attempt (the controller's last_frames_sent/received). Each attempt
  // also re-arms the SDO client's duplicate-answer check (sdo_client.hpp).
  void begin_attempt() {
    attempt_frames_sent_ = attempt_frames_received_ = 0;
    sdo_.begin_attempt();
  }
  uint32_t attempt_frames_sent() const { return attempt_frames_sent_; }
  uint32_t attempt_frames_received() const { return attempt_frames_received_; }

  // Sends in one batch within tx_deadline_us; false (fault raised) if the bus refused.
  bool send(const hal::CanFrame* frames, size_t count);
  // Receives and dispatches frames until wait.done() or `deadline_us`; false on timeout or
  // a fault (fault() says which). Produces the controller's heartbeat on the way.
  bool pump_until(Wait& wait, uint64_t deadline_us);
  // Receives and dispatches for `duration_us` without sending: another master's frames raise
  // kOtherMaster (a fatal fault), so a second controller refuses to start before it sends.
  void listen(uint64_t duration_us);

  // The capture (episode_capture.hpp), which also hears each ground truth and camera frame the
  // current wait did not take: a second answer to a capture that already ended (a second
  // camera, a forged ground truth) is a fault there, as a second answer to an SDO request is.
  void set_capture(Wait* capture) { capture_ = capture; }

  // The services.
  SdoClient& sdo() { return sdo_; }
  NmtMaster& nmt() { return nmt_; }
  HeartbeatConsumer& heartbeats() { return heartbeats_; }
  HeartbeatProducer& heartbeat_producer() { return producer_; }
  // Whether the drives' heartbeat consumers watch this controller (bring-up has written their
  // 0x1016 in this bring-up): before that, an EMCY 0x8130 is a drive that lost the master
  // before this one (a killed controller's, before a --resume), not a fault of this run.
  bool drives_watch_us() const { return drives_watch_us_; }
  void set_drives_watch_us(bool watching) { drives_watch_us_ = watching; }

 private:
  void dispatch(const hal::CanFrame& f, uint64_t now, Wait& wait);
  void other_master(uint8_t node);
  bool decoded(protocol::CodecStatus s);

  hal::CanBus* bus_ = nullptr;
  const ControllerConfig* config_;
  ControllerCounters* counters_;
  CycleProbe* probe_ = nullptr;
  PeriodPacer* pacer_ = nullptr;
  const volatile int* stop_request_ = nullptr;
  protocol::GroundTruthAssembler ground_truth_;  // the classic profile's five frames
  Wait* capture_ = nullptr;

  Fault fault_ = Fault::kNone;
  Fault fatal_ = Fault::kNone;
  bool stopping_ = false;
  uint32_t attempt_frames_sent_ = 0;
  uint32_t attempt_frames_received_ = 0;
  // A time by which the bus's receive queue has been read to its end (the start of the last
  // wait that returned less than a full batch): a node is lost only if it was silent for the
  // heartbeat timeout up to then. Checking against the clock alone would call a
  // node lost whose heartbeats wait in the queue after a long encoder inference (seconds on
  // QEMU under load) that kept the loop from reading the bus.
  uint64_t drained_us_ = 0;
  bool drives_watch_us_ = false;

  SdoClient sdo_{this};
  HeartbeatConsumer heartbeats_{this};
  NmtMaster nmt_{this, &heartbeats_};
  HeartbeatProducer producer_;
  EmcyConsumer emcy_{this};

  static constexpr size_t kRxBatch = 32;
  hal::CanFrame rx_[kRxBatch];
};

}  // namespace curio::app
