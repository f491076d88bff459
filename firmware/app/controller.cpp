#include "firmware/app/controller.hpp"

#include <cmath>

#include "firmware/protocol/arm_objects.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/nn/encoder.hpp"

namespace curio::app {

using hal::CanFrame;
using hal::CanStatus;
using namespace protocol;
using cia402::DriveState;

static_assert(kJoints == kJointNodes, "one CiA 402 node per joint");
static_assert(kLatentDim == nn::kLatents, "the encoder's μ is the learned outcome");
static_assert(kCameraImageBytes == sizeof(uint8_t) * 64 * 64 * 3, "one camera frame");
static_assert(sizeof(Controller) <= 20 * 1024, "controller state (with one camera frame) fits 20 KB of RAM");
static_assert(kJointLimitCounts > 0 && kJointLimitCounts < INT32_MAX / 2, "joint range fits");

namespace {

// Longest single wait for frames: bounds how late a bus-off or a lost heartbeat is noticed.
constexpr uint64_t kMaxWaitUs = 10'000;

// 2π in counts, for the following error of joints whose angle wraps at ±π.
constexpr double kTwoPiCounts = 2.0 * kPi * kCountsPerRad;

// Node id of node index i (0..6 joints, 7 camera).
constexpr uint8_t node_id(int index) {
  return index == kJointNodes ? kCameraNode : static_cast<uint8_t>(kFirstJointNode + index);
}

}  // namespace

const char* to_string(AppStatus s) {
  switch (s) {
    case AppStatus::kOk:
      return "ok";
    case AppStatus::kNotInitialised:
      return "not initialised";
    case AppStatus::kInvalidArgument:
      return "invalid argument";
    case AppStatus::kArmNotReady:
      return "arm not ready";
    case AppStatus::kEpisodeFailed:
      return "episode failed (all attempts hit a fault)";
    case AppStatus::kDone:
      return "done";
    case AppStatus::kExplorerError:
      return "explorer error";
  }
  return "?";
}

const char* to_string(Fault f) {
  switch (f) {
    case Fault::kNone:
      return "none";
    case Fault::kSdoTimeout:
      return "sdo_timeout";
    case Fault::kSdoAbort:
      return "sdo_abort";
    case Fault::kBootTimeout:
      return "boot_timeout";
    case Fault::kHeartbeatLost:
      return "heartbeat_lost";
    case Fault::kNodeState:
      return "node_state";
    case Fault::kEmergency:
      return "emergency";
    case Fault::kDriveFault:
      return "drive_fault";
    case Fault::kFeedbackTimeout:
      return "feedback_timeout";
    case Fault::kFollowingError:
      return "following_error";
    case Fault::kJointLimit:
      return "joint_limit";
    case Fault::kBusOff:
      return "bus_off";
    case Fault::kSendFailed:
      return "send_failed";
    case Fault::kCaptureTimeout:
      return "capture_timeout";
    case Fault::kImageError:
      return "image_error";
    case Fault::kGroundTruthInvalid:
      return "ground_truth_invalid";
    case Fault::kEncoderFailed:
      return "encoder_failed";
    case Fault::kCount:
      break;
  }
  return "?";
}

Controller::Controller() : image_rx_(camera_link_for_controller(), image_, sizeof image_) {}

int Controller::node_index(uint8_t node) {
  if (is_joint_node(node)) return node - kFirstJointNode;
  if (node == kCameraNode) return kCameraIndex;
  return -1;
}

AppStatus Controller::init(hal::CanBus* bus, Explorer* explorer, const ControllerConfig& config,
                           nn::Encoder* encoder) {
  initialised_ = false;
  arm_ready_ = false;
  if (bus == nullptr || explorer == nullptr || !explorer->initialised())
    return AppStatus::kInvalidArgument;
  const int dim = explorer->config().outcome_dim;
  if (encoder != nullptr ? dim != kLatentDim : dim != kEfrOutcomeDim)
    return AppStatus::kInvalidArgument;
  if (config.max_attempts == 0 || config.capture_attempts == 0) return AppStatus::kInvalidArgument;
  if (config.joint_limit_counts <= 0 || config.joint_limit_counts > kJointLimitCounts)
    return AppStatus::kInvalidArgument;
  if (config.following_error_counts < 0) return AppStatus::kInvalidArgument;
  bus_ = bus;
  explorer_ = explorer;
  encoder_ = encoder;
  config_ = config;
  if (encoder_ != nullptr) config_.want_image = true;
  counters_ = ControllerCounters{};
  record_ = EpisodeRecord{};
  episode_started_ = false;
  initialised_ = true;
  return AppStatus::kOk;
}

void Controller::raise(Fault f, uint8_t node) {
  if (fault_ != Fault::kNone) return;  // the first fault of an attempt is its cause
  fault_ = f;
  fault_node_ = node;
  ++counters_.faults[static_cast<size_t>(f)];
  ++counters_.fault_total;
  counters_.last_fault = f;
  counters_.last_fault_node = node;
}

bool Controller::send(const CanFrame* frames, size_t count) {
  const hal::BusState state = bus_->state();
  if (state == hal::BusState::kBusOff || state == hal::BusState::kDown) {
    raise(Fault::kBusOff, 0);
    return false;
  }
  size_t accepted = 0;
  const CanStatus s =
      bus_->send_batch(frames, count, bus_->now_us() + config_.tx_deadline_us, &accepted);
  if (s == CanStatus::kOk) accepted = count;
  counters_.frames_sent += accepted;
  attempt_frames_sent_ += static_cast<uint32_t>(accepted);
  if (s == CanStatus::kOk) return true;
  raise(s == CanStatus::kBusOff ? Fault::kBusOff : Fault::kSendFailed, 0);
  return false;
}

bool Controller::wait_done(Wait wait) const {
  switch (wait) {
    case Wait::kSdo:
      for (const SdoPending& p : sdo_)
        if (p.active && !p.done) return false;
      return true;
    case Wait::kFeedback:
      return feedback_mask_ == (1u << kJoints) - 1;
    case Wait::kCapture:
      return ground_truth_ok_ && image_ok_;
    case Wait::kHeartbeats:
      for (int i = 0; i < kNodes; ++i) {
        if (!heard_[i]) return false;
        if (awaited_any_state_) continue;
        if (nmt_state_[i] != awaited_state_) return false;
      }
      return true;
  }
  return false;
}

void Controller::check_heartbeats(uint64_t now) {
  if (!heartbeat_watch_) return;
  for (int i = 0; i < kNodes; ++i) {
    if (now > last_heartbeat_us_[i] + config_.heartbeat_timeout_us) {
      raise(Fault::kHeartbeatLost, node_id(i));
      return;
    }
  }
}

bool Controller::pump_until(Wait wait, uint64_t deadline_us) {
  for (;;) {
    if (fault_ != Fault::kNone) return false;
    if (wait_done(wait)) return true;
    const uint64_t now = bus_->now_us();
    const hal::BusState state = bus_->state();
    if (state == hal::BusState::kBusOff || state == hal::BusState::kDown) {
      raise(Fault::kBusOff, 0);
      return false;
    }
    check_heartbeats(now);
    if (capture_active_ && image_rx_.busy()) {
      IsoTpReply reply;
      if (image_rx_.poll(now, &reply) == IsoTpStatus::kTimeout)
        raise(Fault::kCaptureTimeout, kCameraNode);
      if (reply.valid) send(&reply.frame, 1);
    }
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
      for (size_t i = 0; i < n; ++i) dispatch(rx_[i], at);
    } else if (s == CanStatus::kBusOff || s == CanStatus::kIoError) {
      raise(Fault::kBusOff, 0);
      return false;
    }
  }
}

void Controller::dispatch(const CanFrame& f, uint64_t now) {
  ++counters_.frames_received;
  ++attempt_frames_received_;
  if (f.error()) {
    ++counters_.bus_errors;
    return;
  }
  uint8_t node = 0;
  switch (classify(f, &node)) {
    case MessageKind::kJointFeedback: {
      JointFeedback fb;
      if (decode_joint_feedback(f, &fb) != CodecStatus::kOk) {
        ++counters_.malformed_frames;
        return;
      }
      const auto bit = static_cast<uint8_t>(1u << (fb.node - kFirstJointNode));
      if (!cycle_active_ || (feedback_mask_ & bit) != 0) {
        ++counters_.unexpected_frames;  // stale (an aborted cycle) or duplicate
        return;
      }
      feedback_[fb.node - kFirstJointNode] = fb;
      feedback_mask_ = static_cast<uint8_t>(feedback_mask_ | bit);
      return;
    }
    case MessageKind::kHeartbeat: {
      Heartbeat hb;
      if (decode_heartbeat(f, &hb) != CodecStatus::kOk) {
        ++counters_.malformed_frames;
        return;
      }
      const int i = node_index(hb.node);
      last_heartbeat_us_[i] = now;
      nmt_state_[i] = hb.state;
      heard_[i] = true;
      if (expect_operational_ && hb.state != NmtState::kOperational)
        raise(Fault::kNodeState, hb.node);
      return;
    }
    case MessageKind::kEmcy: {
      Emergency e;
      if (decode_emcy(f, &e) != CodecStatus::kOk) {
        ++counters_.malformed_frames;
        return;
      }
      if (e.error_code == 0) return;  // "error reset / no error"
      ++counters_.emergencies;
      raise(Fault::kEmergency, e.node);
      return;
    }
    case MessageKind::kSdoResponse: {
      SdoMessage m;
      if (decode_sdo(f, &m) != CodecStatus::kOk) {
        ++counters_.malformed_frames;
        return;
      }
      SdoPending& p = sdo_[node_index(m.node)];
      const bool expected_kind =
          m.kind == SdoKind::kNodeAbort ||
          (p.upload ? m.kind == SdoKind::kUploadResponse : m.kind == SdoKind::kDownloadResponse);
      if (!p.active || p.done || p.index != m.index || p.sub != m.subindex || !expected_kind) {
        ++counters_.unexpected_frames;
        return;
      }
      p.done = true;
      p.aborted = m.kind == SdoKind::kNodeAbort;
      p.value = m.value;
      return;
    }
    case MessageKind::kGroundTruth: {
      GroundTruth g;
      if (decode_ground_truth(f, &g) != CodecStatus::kOk) {
        ++counters_.malformed_frames;
        return;
      }
      if (!capture_active_ || g.episode != capture_episode_ || ground_truth_ok_) {
        ++counters_.unexpected_frames;
        return;
      }
      ground_truth_ = g;
      ground_truth_ok_ = true;
      return;
    }
    case MessageKind::kCameraImage: {
      if (!capture_active_ || image_ok_) {
        ++counters_.unexpected_frames;
        return;
      }
      const bool was_busy = image_rx_.busy();
      IsoTpReply reply;
      const IsoTpStatus s = image_rx_.on_frame(f, now, &reply);
      if (reply.valid) send(&reply.frame, 1);
      switch (s) {
        case IsoTpStatus::kComplete:
          if (image_rx_.size() == kCameraImageBytes)
            image_ok_ = true;
          else
            raise(Fault::kImageError, kCameraNode);  // a message, but not one frame
          return;
        case IsoTpStatus::kInProgress:
        case IsoTpStatus::kIgnored:
        case IsoTpStatus::kIdle:
          return;
        case IsoTpStatus::kUnexpected:
          // A consecutive frame of an earlier, abandoned transfer: nothing of ours broke.
          if (!was_busy) {
            ++counters_.unexpected_frames;
            return;
          }
          raise(Fault::kImageError, kCameraNode);
          return;
        default:  // sequence error, truncated, oversized (OVFLW sent), timeout
          raise(Fault::kImageError, kCameraNode);
          return;
      }
    }
    case MessageKind::kForeign:
    case MessageKind::kUnknown:
      ++counters_.foreign_frames;
      return;
    default:
      // NMT, SYNC, RPDO, SDO requests, capture requests, flow control: a master's frames.
      // We never receive our own, so another master is on the bus: not ours to act on.
      ++counters_.foreign_frames;
      return;
  }
}

bool Controller::sdo(uint8_t node, SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                     uint8_t size, uint32_t* read) {
  for (SdoPending& p : sdo_) p = SdoPending{};
  SdoPending& p = sdo_[node_index(node)];
  p.active = true;
  p.upload = kind == SdoKind::kUploadRequest;
  p.index = index;
  p.sub = sub;
  SdoMessage m;
  m.kind = kind;
  m.node = node;
  m.index = index;
  m.subindex = sub;
  m.value = value;
  m.size = size;
  const CanFrame f = encode_sdo(m);
  if (!send(&f, 1)) return false;
  if (!pump_until(Wait::kSdo, bus_->now_us() + config_.sdo_timeout_us)) {
    raise(Fault::kSdoTimeout, node);
    return false;
  }
  if (p.aborted) {
    raise(Fault::kSdoAbort, node);
    return false;
  }
  if (read != nullptr) *read = p.value;
  p.active = false;
  return true;
}

// The same SDO to every joint at once (one batch), then all answers.
bool Controller::sdo_all_joints(SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                                uint8_t size) {
  CanFrame frames[kJoints];
  for (SdoPending& p : sdo_) p = SdoPending{};
  for (int j = 0; j < kJoints; ++j) {
    SdoPending& p = sdo_[j];
    p.active = true;
    p.upload = kind == SdoKind::kUploadRequest;
    p.index = index;
    p.sub = sub;
    SdoMessage m;
    m.kind = kind;
    m.node = node_id(j);
    m.index = index;
    m.subindex = sub;
    m.value = value;
    m.size = size;
    frames[j] = encode_sdo(m);
  }
  if (!send(frames, kJoints)) return false;
  if (!pump_until(Wait::kSdo, bus_->now_us() + config_.sdo_timeout_us)) {
    for (int j = 0; j < kJoints; ++j)
      if (!sdo_[j].done) raise(Fault::kSdoTimeout, node_id(j));
    return false;
  }
  for (int j = 0; j < kJoints; ++j) {
    if (sdo_[j].aborted) {
      raise(Fault::kSdoAbort, node_id(j));
      return false;
    }
  }
  return true;
}

bool Controller::await_nmt(bool any_state, NmtState state) {
  awaited_any_state_ = any_state;
  awaited_state_ = state;
  if (pump_until(Wait::kHeartbeats, bus_->now_us() + config_.boot_timeout_us)) return true;
  for (int i = 0; i < kNodes; ++i)
    if (!heard_[i] || (!any_state && nmt_state_[i] != state))
      raise(Fault::kBootTimeout, node_id(i));
  return false;
}

bool Controller::bring_up(bool reset_nodes) {
  ++counters_.arm_bringups;
  heartbeat_watch_ = false;
  expect_operational_ = false;
  if (reset_nodes) {
    // Reset node: every node (and the simulated world) starts afresh and sends boot-up.
    for (bool& h : heard_) h = false;
    const CanFrame reset = encode_nmt({NmtCommand::kResetNode, 0});
    if (!send(&reset, 1) || !await_nmt(true, NmtState::kBootUp)) return false;
  }
  // Pre-operational (SDO works there, not in "stopped"; PDOs pause), then the configuration:
  // heartbeats, CSP mode, interpolation period 10 ms, camera capture content.
  const CanFrame pre_operational = encode_nmt({NmtCommand::kEnterPreOperational, 0});
  if (!send(&pre_operational, 1)) return false;
  if (!sdo_all_joints(SdoKind::kDownloadRequest, od::kHeartbeatProducerTime, 0,
                      config_.heartbeat_producer_ms, 2) ||
      !sdo_all_joints(SdoKind::kDownloadRequest, cia402::kModesOfOperation, 0,
                      static_cast<uint8_t>(cia402::kModeCyclicSynchronousPosition), 1) ||
      !sdo_all_joints(SdoKind::kDownloadRequest, cia402::kInterpolationTimePeriod,
                      od::kInterpolationPeriodValueSub, 10, 1) ||
      !sdo_all_joints(SdoKind::kDownloadRequest, cia402::kInterpolationTimePeriod,
                      od::kInterpolationPeriodIndexSub, static_cast<uint8_t>(-3 & 0xFF), 1))
    return false;
  const uint8_t content =
      static_cast<uint8_t>(od::kCaptureGroundTruth | (config_.want_image ? od::kCaptureImage : 0));
  if (!sdo(kCameraNode, SdoKind::kDownloadRequest, od::kHeartbeatProducerTime, 0,
           config_.heartbeat_producer_ms, 2) ||
      !sdo(kCameraNode, SdoKind::kDownloadRequest, od::kCaptureContent, 0, content, 1))
    return false;
  // NMT start; wait until every node's heartbeat says operational.
  for (bool& h : heard_) h = false;
  const CanFrame start = encode_nmt({NmtCommand::kStart, 0});
  if (!send(&start, 1) || !await_nmt(false, NmtState::kOperational)) return false;
  const uint64_t now = bus_->now_us();
  for (uint64_t& t : last_heartbeat_us_) t = now;
  heartbeat_watch_ = true;
  expect_operational_ = true;
  return enable_joints();
}

bool Controller::enable_joints() {
  // Fault reset where needed (rising edge of bit 7), then shutdown → switch on → enable.
  if (!sdo_all_joints(SdoKind::kUploadRequest, cia402::kStatusword, 0, 0, 0)) return false;
  bool any_fault = false;
  for (int j = 0; j < kJoints; ++j)
    any_fault = any_fault ||
                cia402::decode_state(static_cast<uint16_t>(sdo_[j].value)) == DriveState::kFault;
  if (any_fault && (!sdo_all_joints(SdoKind::kDownloadRequest, cia402::kControlword, 0,
                                    cia402::kCwDisableVoltage, 2) ||
                    !sdo_all_joints(SdoKind::kDownloadRequest, cia402::kControlword, 0,
                                    cia402::kCwFaultReset, 2)))
    return false;
  if (!sdo_all_joints(SdoKind::kDownloadRequest, cia402::kControlword, 0, cia402::kCwShutdown, 2) ||
      !sdo_all_joints(SdoKind::kDownloadRequest, cia402::kControlword, 0, cia402::kCwSwitchOn, 2) ||
      !sdo_all_joints(SdoKind::kDownloadRequest, cia402::kControlword, 0,
                      cia402::kCwEnableOperation, 2) ||
      !sdo_all_joints(SdoKind::kUploadRequest, cia402::kStatusword, 0, 0, 0))
    return false;
  for (int j = 0; j < kJoints; ++j) {
    if (cia402::decode_state(static_cast<uint16_t>(sdo_[j].value)) !=
        DriveState::kOperationEnabled) {
      raise(Fault::kDriveFault, node_id(j));
      return false;
    }
  }
  return true;
}

AppStatus Controller::start_arm() {
  if (!initialised_) return AppStatus::kNotInitialised;
  fault_ = Fault::kNone;
  arm_ready_ = bring_up(config_.reset_nodes);
  episode_started_ = false;
  return arm_ready_ ? AppStatus::kOk : AppStatus::kArmNotReady;
}

uint8_t Controller::query_physics() {
  if (!initialised_) return od::kPhysicsRealArm;
  const Fault saved = fault_;
  fault_ = Fault::kNone;
  uint32_t value = od::kPhysicsRealArm;
  if (!sdo(kCameraNode, SdoKind::kUploadRequest, od::kSimulatorPhysics, 0, 0, 0, &value))
    value = od::kPhysicsRealArm;
  fault_ = saved;
  return static_cast<uint8_t>(value);
}

void Controller::stop_arm() {
  if (!initialised_) return;
  heartbeat_watch_ = false;
  expect_operational_ = false;
  const CanFrame stop = encode_nmt({NmtCommand::kStop, 0});
  send(&stop, 1);
  arm_ready_ = false;
}

bool Controller::recover() {
  const uint64_t deadline = bus_->now_us() + config_.recovery_timeout_us;
  while (bus_->now_us() < deadline) {
    fault_ = Fault::kNone;
    const hal::BusState state = bus_->state();
    if (state == hal::BusState::kBusOff || state == hal::BusState::kDown) {
      // Wait for the controller to come back on the bus (frames still pass meanwhile).
      bus_->wait_readable(1'000);
      continue;
    }
    if (bring_up(false)) return true;
  }
  return false;
}

bool Controller::run_cycle(int t, const float theta[kThetaDim]) {
  if (probe_ != nullptr) probe_->cycle_work_begin();
  float commands[kJoints];
  primitive_.commands(theta, t, commands);
  for (int j = 0; j < kJoints; ++j) {
    int32_t counts = 0;
    if (command_to_counts(commands[j], &counts) != CodecStatus::kOk ||
        !within_joint_limits(counts, config_.joint_limit_counts)) {
      // Not sent: the joints keep the last safe targets; the attempt ends here.
      raise(Fault::kJointLimit, node_id(j));
      if (probe_ != nullptr) probe_->cycle_work_end();
      return false;
    }
    targets_[j] = counts;
  }
  CanFrame frames[kJoints + 1];
  for (int j = 0; j < kJoints; ++j)
    frames[j] = encode_joint_command({node_id(j), cia402::kCwEnableOperation, targets_[j]});
  sync_counter_ = static_cast<uint8_t>(sync_counter_ >= kSyncCounterMax ? 1 : sync_counter_ + 1);
  frames[kJoints] = encode_sync(sync_counter_);
  feedback_mask_ = 0;
  cycle_active_ = true;
  bool ok = send(frames, kJoints + 1);
  if (ok) {
    for (int j = 0; j < kJoints; ++j) safe_targets_[j] = targets_[j];
    ok = pump_until(Wait::kFeedback, bus_->now_us() + config_.feedback_timeout_us);
    if (!ok) {
      for (int j = 0; j < kJoints; ++j)
        if ((feedback_mask_ & (1u << j)) == 0) raise(Fault::kFeedbackTimeout, node_id(j));
    }
  }
  cycle_active_ = false;
  if (ok) {
    for (int j = 0; j < kJoints && ok; ++j) {
      const JointFeedback& fb = feedback_[j];
      if (cia402::decode_state(fb.statusword) != DriveState::kOperationEnabled) {
        raise(Fault::kDriveFault, fb.node);
        ok = false;
        break;
      }
      const double error = std::remainder(
          static_cast<double>(static_cast<int64_t>(fb.actual_counts) - targets_[j]), kTwoPiCounts);
      if (std::fabs(error) > static_cast<double>(config_.following_error_counts)) {
        raise(Fault::kFollowingError, fb.node);
        ok = false;
      }
    }
  }
  if (ok) ++counters_.sync_cycles;
  if (probe_ != nullptr) probe_->cycle_work_end();
  return ok;
}

bool Controller::capture(uint32_t episode, float* outcome) {
  capture_active_ = true;
  capture_episode_ = episode;
  ground_truth_ok_ = false;
  image_ok_ = !config_.want_image;
  image_rx_.reset();
  const CanFrame request = encode_camera_capture({episode});
  bool ok =
      send(&request, 1) && pump_until(Wait::kCapture, bus_->now_us() + config_.capture_timeout_us);
  capture_active_ = false;
  if (!ok) {
    raise(Fault::kCaptureTimeout, kCameraNode);
    return false;
  }
  const GroundTruth& g = ground_truth_;
  if (!std::isfinite(g.ball_x) || !std::isfinite(g.ball_y) || !std::isfinite(g.distractor_x) ||
      !std::isfinite(g.distractor_y)) {
    raise(Fault::kGroundTruthInvalid, kCameraNode);
    return false;
  }
  if (encoder_ != nullptr) {
    if (encoder_->encode(image_, outcome) != nn::Status::kOk) {
      raise(Fault::kEncoderFailed, kCameraNode);
      return false;
    }
  } else {
    outcome[kEfrDistractorX] = static_cast<float>(g.distractor_x);
    outcome[kEfrDistractorY] = static_cast<float>(g.distractor_y);
    outcome[kEfrBallX] = static_cast<float>(g.ball_x);
    outcome[kEfrBallY] = static_cast<float>(g.ball_y);
  }
  record_.ball[0] = static_cast<float>(g.ball_x);
  record_.ball[1] = static_cast<float>(g.ball_y);
  record_.distractor[0] = static_cast<float>(g.distractor_x);
  record_.distractor[1] = static_cast<float>(g.distractor_y);
  record_.grasped = g.ball_grasped;
  return true;
}

bool Controller::run_attempt(const float theta[kThetaDim], float* outcome) {
  fault_ = Fault::kNone;
  attempt_frames_sent_ = 0;
  attempt_frames_received_ = 0;
  // Scene reset (the same episode number again: the camera node replays the episode).
  if (!sdo(kCameraNode, SdoKind::kDownloadRequest, od::kEpisodeControl, od::kEpisodeStartSub,
           episode_number_, 4))
    return false;
  for (int t = 0; t < kStepsPerEpisode; ++t)
    if (!run_cycle(t, theta)) return false;
  for (int c = 0;; ++c) {
    if (capture(episode_number_, outcome)) return true;
    const bool capture_fault = fault_ == Fault::kCaptureTimeout || fault_ == Fault::kImageError;
    if (!capture_fault || c + 1 >= config_.capture_attempts) return false;
    ++counters_.capture_retries;
    fault_ = Fault::kNone;  // counted; the capture is attempted again
  }
}

AppStatus Controller::run_episode() {
  if (!initialised_) return AppStatus::kNotInitialised;
  if (explorer_->done()) return AppStatus::kDone;
  if (!arm_ready_) {
    fault_ = Fault::kNone;
    arm_ready_ = recover();
    if (!arm_ready_) return AppStatus::kArmNotReady;
  }
  float theta[kThetaDim];
  if (explorer_->propose(theta) != Status::kOk) return AppStatus::kExplorerError;
  record_ = EpisodeRecord{};
  record_.episode = explorer_->episode();
  record_.kind = explorer_->kind();
  record_.module = explorer_->module();
  record_.exploit = record_.kind == EpisodeKind::kExploit && record_.module >= 0;
  episode_number_ = static_cast<uint32_t>(record_.episode);
  float outcome[kMaxOutcomeDim] = {};
  bool ok = false;
  for (int attempt = 1; attempt <= config_.max_attempts; ++attempt) {
    ++counters_.attempts;
    if (attempt > 1) ++counters_.replays;
    record_.attempts = attempt;
    ok = run_attempt(theta, outcome);
    if (ok) break;
    // Hold: nothing more goes to the joints. Bring the arm back, then replay the episode.
    if (attempt == config_.max_attempts) break;
    if (!recover()) {
      arm_ready_ = false;
      break;
    }
  }
  if (!ok) {
    // Nothing archived; the episode stays pending (propose() returns the same θ again).
    arm_ready_ = arm_ready_ && fault_ == Fault::kNone;
    return AppStatus::kEpisodeFailed;
  }
  if (explorer_->observe(outcome) != Status::kOk) return AppStatus::kExplorerError;
  ++counters_.episodes;
  record_.progress = record_.exploit ? explorer_->last_progress() : 0.0f;
  record_.outcome_dim = explorer_->config().outcome_dim;
  for (int i = 0; i < record_.outcome_dim; ++i) record_.outcome[i] = outcome[i];
  return AppStatus::kOk;
}

}  // namespace curio::app
