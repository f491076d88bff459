// The controller's CANopen master: dispatch, SDO client, NMT, heartbeat consumer.
#include "firmware/app/canopen_master.hpp"

namespace curio::app {

using hal::CanFrame;
using hal::CanStatus;
using namespace protocol;

namespace {

// Longest single wait for frames: bounds how late a bus-off or a lost heartbeat is noticed.
constexpr uint64_t kMaxWaitUs = 10'000;

// Node i is not on this bus: the camera when a camera on the controller's computer replaces it.
bool not_on_bus(const ControllerConfig& config, int i) {
  return i == kCameraIndex && !config.camera_on_bus;
}

}  // namespace

// Every pending SDO transfer answered.
class CanOpenMaster::SdoWait final : public Wait {
 public:
  explicit SdoWait(const CanOpenMaster& m) : m_(m) {}
  bool done() const override {
    for (const SdoPending& p : m_.sdo_)
      if (p.active && !p.done) return false;
    return true;
  }

 private:
  const CanOpenMaster& m_;
};

// A heartbeat from every node since the last NMT command (in `state`, unless any_state).
class CanOpenMaster::NmtWait final : public Wait {
 public:
  NmtWait(const CanOpenMaster& m, bool any_state, NmtState state)
      : m_(m), any_state_(any_state), state_(state) {}
  bool done() const override {
    for (int i = 0; i < kArmNodes; ++i) {
      if (not_on_bus(*m_.config_, i)) continue;
      if (!m_.heard_[i]) return false;
      if (any_state_) continue;
      if (m_.nmt_state_[i] != state_) return false;
    }
    return true;
  }

 private:
  const CanOpenMaster& m_;
  bool any_state_;
  NmtState state_;
};

void CanOpenMaster::listen(uint64_t duration_us) {
  class Listening final : public Wait {
   public:
    bool done() const override { return false; }
  } listening;
  pump_until(listening, bus_->now_us() + duration_us);
}

int CanOpenMaster::node_index(uint8_t node) {
  if (is_joint_node(node)) return node - kFirstJointNode;
  if (node == kCameraNode) return kCameraIndex;
  return -1;
}

bool CanOpenMaster::bus_off() const {
  const hal::BusState state = bus_->state();
  return state == hal::BusState::kBusOff || state == hal::BusState::kDown;
}

void CanOpenMaster::raise(Fault f, uint8_t node) {
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

bool CanOpenMaster::send_nmt(NmtCommand command) {
  for (bool& op : operational_since_nmt_) op = false;  // the nodes may leave operational now
  const CanFrame f = encode_nmt({command, 0});
  return send(&f, 1);
}

void CanOpenMaster::check_heartbeats(uint64_t now) {
  if (!heartbeat_watch_) return;
  for (int i = 0; i < kArmNodes; ++i) {
    if (not_on_bus(*config_, i)) continue;
    if (now > last_heartbeat_us_[i] + config_->heartbeat_timeout_us) {
      raise(Fault::kHeartbeatLost, node_id(i));
      return;
    }
  }
}

bool CanOpenMaster::pump_until(Wait& wait, uint64_t deadline_us) {
  for (;;) {
    if (fault_ != Fault::kNone) return false;
    if (wait.done()) return true;
    const uint64_t now = bus_->now_us();
    if (bus_off()) {
      raise(Fault::kBusOff, 0);
      return false;
    }
    check_heartbeats(now);
    wait.poll(now);
    if (fault_ != Fault::kNone) return false;
    if (now >= deadline_us) return false;
    // Wake up now and then to re-check the heartbeat consumer and the bus state (bus-off
    // arrives as a state, not as a frame, on some backends).
    const uint64_t timeout = deadline_us - now < kMaxWaitUs ? deadline_us - now : kMaxWaitUs;
    size_t n = 0;
    if (probe_ != nullptr) probe_->cycle_wait_begin();
    const CanStatus s = bus_->receive_wait(rx_, kRxBatch, &n, timeout);
    if (probe_ != nullptr) probe_->cycle_wait_end();
    if (s == CanStatus::kOk) {
      const uint64_t at = bus_->now_us();
      for (size_t i = 0; i < n; ++i) dispatch(rx_[i], at, wait);
    } else if (s == CanStatus::kBusOff || s == CanStatus::kIoError) {
      raise(Fault::kBusOff, 0);
      return false;
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
      if (decoded(decode_heartbeat(f, &hb))) on_heartbeat(hb, now);
      return;
    }
    case MessageKind::kEmcy: {
      Emergency e;
      if (!decoded(decode_emcy(f, &e))) return;
      if (e.error_code == 0) return;  // "error reset / no error"
      ++counters_->emergencies;
      raise(Fault::kEmergency, e.node);
      return;
    }
    case MessageKind::kSdoResponse: {
      SdoMessage m;
      if (!decoded(decode_sdo(f, &m))) return;
      expected = on_sdo_response(m);
      break;
    }
    case MessageKind::kGroundTruth: {
      GroundTruth g;
      bool complete = false;
      if (!decoded(ground_truth_.on_frame(f, &g, &complete))) return;
      if (!complete) return;  // a classic part: the message is not whole yet
      expected = wait.on_ground_truth(g);
      break;
    }
    case MessageKind::kCameraImage:
      expected = wait.on_camera_frame(f, now);
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

void CanOpenMaster::on_heartbeat(const Heartbeat& hb, uint64_t now) {
  const int i = node_index(hb.node);
  if (hb.state == NmtState::kBootUp && !boot_up_expected_) ++counters_->node_reboots;
  last_heartbeat_us_[i] = now;
  nmt_state_[i] = hb.state;
  heard_[i] = true;
  if (hb.state == NmtState::kOperational) {
    operational_since_nmt_[i] = true;
  } else if (operational_since_nmt_[i]) {
    // Pre-operational, stopped or a boot-up after operational: the node was not told to
    // leave (our NMT commands clear operational_since_nmt_), so it left on an error, restarted,
    // or a second node with this id answers (its heartbeat from before our command, or its
    // boot-up after our reset, comes late).
    operational_since_nmt_[i] = false;
    ++counters_->state_regressions;
    counters_->last_regression_node = hb.node;
  }
  if (expect_operational_ && hb.state != NmtState::kOperational) raise(Fault::kNodeState, hb.node);
}

bool CanOpenMaster::SdoPending::is_answer(const SdoMessage& m) const {
  const bool expected_kind =
      m.kind == SdoKind::kNodeAbort ||
      (upload ? m.kind == SdoKind::kUploadResponse : m.kind == SdoKind::kDownloadResponse);
  return active && index == m.index && sub == m.subindex && expected_kind;
}

void CanOpenMaster::begin_transfers() {
  for (int i = 0; i < kArmNodes; ++i) {
    if (sdo_[i].done) answered_[i] = sdo_[i];
    sdo_[i] = SdoPending{};
  }
}

// false: no transfer of ours is waiting for this answer.
bool CanOpenMaster::on_sdo_response(const SdoMessage& m) {
  const int i = node_index(m.node);
  SdoPending& p = sdo_[i];
  const bool pending = p.is_answer(m);
  // A CANopen SDO server answers each request once: a second answer is a second node with
  // this id (two arms on one bus), unless our request timed out (its late answer). It may come
  // while the transfer is still ours, or, from a slower second node, after we moved on.
  const SdoPending& before = answered_[i];
  if (pending ? p.done : before.done && before.is_answer(m)) {
    ++counters_->duplicate_answers;
    if (!sdo_timed_out_[i]) raise(Fault::kDuplicateNode, m.node);
    return false;
  }
  if (!pending) return false;
  p.done = true;
  p.aborted = m.kind == SdoKind::kNodeAbort;
  p.value = m.value;
  return true;
}

// Marks transfer p (node's) pending and returns its request frame.
CanFrame CanOpenMaster::sdo_request(SdoPending& p, uint8_t node, SdoKind kind, uint16_t index,
                                    uint8_t sub, uint32_t value, uint8_t size) {
  p.active = true;
  p.upload = kind == SdoKind::kUploadRequest;
  p.index = index;
  p.sub = sub;
  return encode_sdo({kind, node, index, sub, value, size});
}

bool CanOpenMaster::sdo(uint8_t node, SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                        uint8_t size, uint32_t* read) {
  begin_transfers();
  SdoPending& p = sdo_[node_index(node)];
  const CanFrame f = sdo_request(p, node, kind, index, sub, value, size);
  if (!send(&f, 1)) return false;
  SdoWait answered(*this);
  if (!pump_until(answered, bus_->now_us() + config_->sdo_timeout_us)) {
    if (!p.done) sdo_timed_out_[node_index(node)] = true;
    raise(Fault::kSdoTimeout, node);
    return false;
  }
  if (p.aborted) {
    raise(Fault::kSdoAbort, node);
    return false;
  }
  if (read != nullptr) *read = p.value;
  return true;
}

bool CanOpenMaster::sdo_all_joints(SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                                   uint8_t size) {
  CanFrame frames[kJointNodes];
  begin_transfers();
  for (int j = 0; j < kJointNodes; ++j)
    frames[j] = sdo_request(sdo_[j], node_id(j), kind, index, sub, value, size);
  if (!send(frames, kJointNodes)) return false;
  SdoWait answered(*this);
  if (!pump_until(answered, bus_->now_us() + config_->sdo_timeout_us)) {
    for (int j = 0; j < kJointNodes; ++j) {
      if (sdo_[j].done) continue;
      sdo_timed_out_[j] = true;
      raise(Fault::kSdoTimeout, node_id(j));
    }
    return false;
  }
  for (int j = 0; j < kJointNodes; ++j) {
    if (sdo_[j].aborted) {
      raise(Fault::kSdoAbort, node_id(j));
      return false;
    }
  }
  return true;
}

void CanOpenMaster::forget_heartbeats() {
  for (bool& h : heard_) h = false;
}

bool CanOpenMaster::await_nmt(bool any_state, NmtState state) {
  NmtWait wait(*this, any_state, state);
  if (pump_until(wait, bus_->now_us() + config_->boot_timeout_us)) return true;
  for (int i = 0; i < kArmNodes; ++i)
    if (!not_on_bus(*config_, i) && (!heard_[i] || (!any_state && nmt_state_[i] != state)))
      raise(Fault::kBootTimeout, node_id(i));
  return false;
}

void CanOpenMaster::start_heartbeat_watch() {
  const uint64_t now = bus_->now_us();
  for (uint64_t& t : last_heartbeat_us_) t = now;
  heartbeat_watch_ = true;
  expect_operational_ = true;
}

void CanOpenMaster::stop_heartbeat_watch() {
  heartbeat_watch_ = false;
  expect_operational_ = false;
}

}  // namespace curio::app
