// The controller's CANopen master: the pump, the dispatcher and the attempt's fault. The
// services live in their own files (canopen_master.hpp lists them).
#include "firmware/app/canopen_master.hpp"

namespace curio::app {

using hal::CanFrame;
using hal::CanStatus;
using namespace protocol;

namespace {

// Longest single wait for frames: bounds how late a bus-off, a lost heartbeat or a stop
// request is noticed.
constexpr uint64_t kMaxWaitUs = 10'000;

}  // namespace

void CanOpenMaster::listen(uint64_t duration_us) {
  class Listening final : public Wait {
   public:
    bool done() const override { return false; }
  } listening;
  pump_until(listening, bus_->now_us() + duration_us);
}

bool CanOpenMaster::bus_off() const {
  const hal::BusState state = bus_->state();
  return state == hal::BusState::kBusOff || state == hal::BusState::kDown;
}

void CanOpenMaster::raise(Fault f, uint8_t node) {
  if (stopping_) {
    // The controlled stop goes on: counted, no cause.
    ++counters_->faults[static_cast<size_t>(f)];
    ++counters_->fault_total;
    return;
  }
  if (is_fatal(f) && fatal_ == Fault::kNone) {
    fatal_ = f;
    fault_ = Fault::kNone;  // the cause now, whatever came first
  }
  if (fault_ != Fault::kNone) return;  // the first fault of an attempt is its cause
  fault_ = f;
  ++counters_->faults[static_cast<size_t>(f)];
  ++counters_->fault_total;
  counters_->last_fault = f;
  counters_->last_fault_node = node;
}

bool CanOpenMaster::send(const CanFrame* frames, size_t count) {
  if (bus_off()) {
    raise(Fault::kBusOff, 0);
    return false;
  }
  size_t accepted = 0;
  const CanStatus s =
      bus_->send_batch(frames, count, bus_->now_us() + config_->tx_deadline_us, &accepted);
  if (s == CanStatus::kOk) accepted = count;
  counters_->frames_sent += accepted;
  attempt_frames_sent_ += static_cast<uint32_t>(accepted);
  if (s == CanStatus::kOk) return true;
  raise(s == CanStatus::kBusOff ? Fault::kBusOff : Fault::kSendFailed, 0);
  return false;
}

bool CanOpenMaster::pump_until(Wait& wait, uint64_t deadline_us) {
  // While stopping, the attempt's cause stays set and later faults set none: only the wait's end,
  // its deadline or a bus that is off end the pump.
  const auto faulted = [this] { return fault_ != Fault::kNone && !stopping_; };
  for (;;) {
    if (faulted()) return false;
    if (wait.done()) return true;
    const uint64_t now = bus_->now_us();
    if (producer_.poll(*bus_, now)) ++counters_->heartbeats_sent;
    if (bus_off()) {
      raise(Fault::kBusOff, 0);
      return false;
    }
    if (!stopping_ && stop_requested()) raise(Fault::kStopRequested, 0);
    heartbeats_.check(drained_us_);
    wait.poll(now);
    if (faulted()) return false;
    if (now >= deadline_us) return false;
    // Wake up now and then to re-check the heartbeat consumer, the bus state (bus-off arrives
    // as a state, not as a frame, on some backends) and a stop request, and for our heartbeat.
    uint64_t timeout = deadline_us - now < kMaxWaitUs ? deadline_us - now : kMaxWaitUs;
    const uint64_t heartbeat_due = producer_.next_due_us();
    if (heartbeat_due > now && heartbeat_due - now < timeout) timeout = heartbeat_due - now;
    size_t n = 0;
    if (probe_ != nullptr) probe_->cycle_wait_begin();
    const CanStatus s = bus_->receive_wait(rx_, kRxBatch, &n, timeout);
    if (probe_ != nullptr) probe_->cycle_wait_end();
    if (s == CanStatus::kOk) {
      const uint64_t at = bus_->now_us();
      for (size_t i = 0; i < n; ++i) dispatch(rx_[i], at, wait);
      // Everything queued before `now` has been read, unless a full batch left some behind.
      if (n < kRxBatch) drained_us_ = now;
    } else if (s == CanStatus::kBusOff || s == CanStatus::kIoError) {
      raise(Fault::kBusOff, 0);
      return false;
    } else if (s == CanStatus::kTimeout || s == CanStatus::kEmpty) {
      drained_us_ = now;  // waited the timeout out: nothing was pending
    }
  }
}

// Our ids, but not decodable (DLC, format, reserved bits): counted, then dropped.
bool CanOpenMaster::decoded(CodecStatus s) {
  if (s == CodecStatus::kOk) return true;
  ++counters_->malformed_frames;
  return false;
}

void CanOpenMaster::dispatch(const CanFrame& f, uint64_t now, Wait& wait) {
  ++counters_->frames_received;
  ++attempt_frames_received_;
  if (f.error()) {
    ++counters_->bus_errors;
    return;
  }
  uint8_t node = 0;
  bool expected = true;
  switch (classify(f, &node)) {
    case MessageKind::kJointFeedback: {
      JointFeedback fb;
      if (!decoded(decode_joint_feedback(f, &fb))) return;
      expected = wait.on_feedback(fb);
      break;
    }
    case MessageKind::kHeartbeat: {
      Heartbeat hb;
      if (decoded(decode_heartbeat(f, &hb))) heartbeats_.on_heartbeat(hb, now);
      return;
    }
    case MessageKind::kEmcy: {
      Emergency e;
      if (decoded(decode_emcy(f, &e))) emcy_.on_emcy(e);
      return;
    }
    case MessageKind::kSdoResponse: {
      SdoMessage m;
      if (!decoded(decode_sdo(f, &m))) return;
      expected = sdo_.on_response(m);
      break;
    }
    case MessageKind::kGroundTruth: {
      GroundTruth g;
      bool complete = false;
      if (!decoded(ground_truth_.on_frame(f, &g, &complete))) return;
      if (!complete) return;  // a classic part: the message is not whole yet
      expected = wait.on_ground_truth(g);
      if (!expected && capture_ != nullptr && capture_ != &wait) capture_->on_ground_truth(g);
      break;
    }
    case MessageKind::kCameraImage:
      expected = wait.on_camera_frame(f, now);
      if (!expected && capture_ != nullptr && capture_ != &wait) capture_->on_camera_frame(f, now);
      break;
    case MessageKind::kNmt:
    case MessageKind::kSync:
    case MessageKind::kJointCommand:
    case MessageKind::kSdoRequest:
    case MessageKind::kCameraCapture:
    case MessageKind::kCameraFlowControl:
      // A master's frames. We never receive our own, so another master drives this arm: its
      // SYNCs step the world, its episode starts and resets change the scene under ours.
      ++counters_->foreign_frames;
      other_master(node);
      return;
    case MessageKind::kForeign:
      ++counters_->foreign_frames;
      // Our own heartbeat's id from someone else: another master with our node id.
      if (f.id == kCobHeartbeat + config_->drives.master_node)
        other_master(config_->drives.master_node);
      return;
    case MessageKind::kUnknown:
    default:
      // Other nodes and unknown ids: not ours to act on.
      ++counters_->foreign_frames;
      return;
  }
  if (!expected) ++counters_->unexpected_frames;
}

void CanOpenMaster::other_master(uint8_t node) {
  ++counters_->other_master_frames;
  raise(Fault::kOtherMaster, node);
}

}  // namespace curio::app
