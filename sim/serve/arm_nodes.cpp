#include "sim/serve/arm_nodes.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

#include "firmware/protocol/arm_objects.hpp"
#include "firmware/app/joint_target.hpp"

namespace curio::sim::serve {

using hal::CanFrame;
using hal::CanStatus;
using namespace protocol;
namespace od = protocol::od;
using cia402::DriveState;

namespace {

constexpr uint64_t kTxDeadlineUs = 100'000;
constexpr uint64_t kTickUs = 1'000;
constexpr uint8_t kErrorRegisterGeneric = 0x01;

// The object index of an SDO request the codec refused (for the abort answer).
uint16_t get_le16_index(const CanFrame& f) {
  return f.len >= 3 ? static_cast<uint16_t>(f.data[1] | (f.data[2] << 8)) : uint16_t{0};
}

}  // namespace

ArmNodes::ArmNodes(hal::CanBus* bus, const ServeOptions& options)
    : bus_(bus),
      options_(options),
      world_(make_world(options.physics, options.world, world_seed_for_run(options.seed))),
      image_(std::make_unique<Image>()),
      frame_(std::make_unique<CameraFrame>()),
      image_sender_(camera_link_for_camera()) {
  for (int j = 0; j < kJointNodes; ++j) joints_[j].id = static_cast<uint8_t>(kFirstJointNode + j);
  camera_.id = kCameraNode;
  // Power-on: every node announces itself (boot-up) and enters pre-operational.
  for (Joint& j : joints_) set_nmt(&j, NmtState::kPreOperational);
  set_nmt(&camera_, NmtState::kPreOperational);
  flush();
}

ArmNodes::~ArmNodes() = default;

ArmNodes::Node* ArmNodes::node(uint8_t id) {
  if (is_joint_node(id)) return &joints_[id - kFirstJointNode];
  if (id == kCameraNode) return &camera_;
  return nullptr;
}

void ArmNodes::queue(const CanFrame& f) {
  tx_[tx_count_++] = f;
  if (tx_count_ == kBatch) flush();
}

void ArmNodes::flush() {
  if (tx_count_ == 0) return;
  size_t accepted = 0;
  const CanStatus s = bus_->send_batch(tx_, tx_count_, bus_->now_us() + kTxDeadlineUs, &accepted);
  if (s == CanStatus::kOk) accepted = tx_count_;
  counters_.frames_out += accepted;
  counters_.tx_failures += tx_count_ - accepted;
  tx_count_ = 0;
}

void ArmNodes::send_heartbeat(Node* n) {
  queue(encode_heartbeat({n->id, n->nmt}));
  ++counters_.heartbeats_sent;
  if (n->heartbeat_ms > 0) n->next_heartbeat_us = bus_->now_us() + n->heartbeat_ms * 1000ull;
}

void ArmNodes::set_nmt(Node* n, NmtState state) {
  if (state == NmtState::kPreOperational && n->nmt == NmtState::kBootUp) {
    // Boot-up message, sent whatever the heartbeat configuration (CiA 301).
    queue(encode_heartbeat({n->id, NmtState::kBootUp}));
    ++counters_.heartbeats_sent;
  }
  const bool changed = n->nmt != state;
  n->nmt = state;
  // Heartbeat at once on a state change, so a master sees it without waiting a period.
  if (changed && n->heartbeat_ms > 0) send_heartbeat(n);
}

void ArmNodes::heartbeats_due(uint64_t now) {
  auto due = [&](Node* n) {
    if (n->heartbeat_ms == 0 || n->nmt == NmtState::kBootUp || now < n->next_heartbeat_us) return;
    send_heartbeat(n);
  };
  for (Joint& j : joints_) due(&j);
  due(&camera_);
}

uint64_t ArmNodes::next_due_us(uint64_t now) const {
  uint64_t next = UINT64_MAX;
  auto consider = [&](const Node& n) {
    if (n.heartbeat_ms > 0 && n.nmt != NmtState::kBootUp)
      next = std::min(next, n.next_heartbeat_us);
  };
  for (const Joint& j : joints_) consider(j);
  consider(camera_);
  if (image_sender_.busy()) next = std::min(next, std::max(now, image_sender_.next_event_us()));
  return next;
}

CanStatus ArmNodes::poll(uint64_t timeout_us) {
  uint64_t now = bus_->now_us();
  heartbeats_due(now);
  pump_image(now);
  flush();
  // Wait the caller's timeout, or in 1 ms ticks when a heartbeat or image frame is due
  // sooner: a small set of wait values, so socket backends need not re-arm their timeout on
  // every call (one syscall each).
  const uint64_t due = next_due_us(now);
  const uint64_t wait =
      due <= now ? 0 : (due - now >= timeout_us ? timeout_us : std::min(timeout_us, kTickUs));
  size_t n = 0;
  const CanStatus s = bus_->receive_wait(rx_, kBatch, &n, wait);
  if (s == CanStatus::kOk) {
    counters_.frames_in += n;
    for (size_t i = 0; i < n; ++i) handle(rx_[i]);
  }
  now = bus_->now_us();
  pump_image(now);
  heartbeats_due(now);
  flush();
  return s;
}

void ArmNodes::run(const std::atomic<bool>& stop) {
  while (!stop.load(std::memory_order_relaxed)) {
    const CanStatus s = poll(50'000);
    if (s != CanStatus::kOk && s != CanStatus::kTimeout && s != CanStatus::kEmpty) {
      // Bus-off, interface down, transport error: nothing to do but wait for recovery.
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
}

void ArmNodes::handle(const CanFrame& f) {
  if (f.error()) {
    ++counters_.malformed;
    return;
  }
  uint8_t id = 0;
  const MessageKind kind = classify(f, &id);
  switch (kind) {
    case MessageKind::kNmt: {
      NmtMessage m;
      if (decode_nmt(f, &m) == CodecStatus::kOk)
        on_nmt(m);
      else
        ++counters_.malformed;
      return;
    }
    case MessageKind::kSync: {
      uint8_t counter = 0;
      if (decode_sync(f, &counter) == CodecStatus::kOk)
        on_sync();
      else
        ++counters_.malformed;
      return;
    }
    case MessageKind::kJointCommand: {
      JointCommand c;
      if (decode_joint_command(f, &c) == CodecStatus::kOk)
        on_joint_command(c);
      else
        ++counters_.malformed;
      return;
    }
    case MessageKind::kSdoRequest: {
      SdoMessage m;
      const CodecStatus s = decode_sdo(f, &m);
      if (s == CodecStatus::kOk) {
        on_sdo(m);
      } else if (s == CodecStatus::kUnsupported || s == CodecStatus::kBadCommand) {
        // Segmented/block transfers or unknown specifiers: refuse, as a real node would.
        SdoMessage abort;
        abort.kind = SdoKind::kNodeAbort;
        abort.node = id;
        abort.index = get_le16_index(f);
        abort.subindex = f.len >= 4 ? f.data[3] : 0;
        abort.value = kSdoAbortBadCommand;
        queue(encode_sdo(abort));
        ++counters_.sdo_aborts;
      } else {
        ++counters_.malformed;
      }
      return;
    }
    case MessageKind::kCameraCapture: {
      CameraCapture c;
      if (decode_camera_capture(f, &c) == CodecStatus::kOk)
        on_capture(c);
      else
        ++counters_.malformed;
      return;
    }
    case MessageKind::kCameraFlowControl: {
      const IsoTpStatus s = image_sender_.on_frame(f, bus_->now_us());
      if (s != IsoTpStatus::kInProgress && s != IsoTpStatus::kIgnored &&
          s != IsoTpStatus::kComplete && s != IsoTpStatus::kIdle)
        ++counters_.image_errors;
      return;
    }
    default:
      // Other nodes' traffic (TPDOs, heartbeats, EMCY, SDO responses of foreign nodes, or
      // frames a fake node sends with our nodes' ids), unknown identifiers.
      ++counters_.foreign;
      return;
  }
}

void ArmNodes::on_nmt(const NmtMessage& m) {
  auto apply = [&](Node* n) {
    switch (m.command) {
      case NmtCommand::kStart:
        set_nmt(n, NmtState::kOperational);
        break;
      case NmtCommand::kStop:
        set_nmt(n, NmtState::kStopped);
        break;
      case NmtCommand::kEnterPreOperational:
        set_nmt(n, NmtState::kPreOperational);
        break;
      case NmtCommand::kResetNode:
      case NmtCommand::kResetCommunication: {
        // Reset: the node's configuration is lost and it boots again. Resetting the camera
        // node (application) also restarts the world from its seed: a fresh run.
        const bool application = m.command == NmtCommand::kResetNode;
        n->heartbeat_ms = 0;
        n->nmt = NmtState::kBootUp;
        if (n == &camera_) {
          if (application) {
            world_ =
                make_world(options_.physics, options_.world, world_seed_for_run(options_.seed));
            camera_.capture_content = od::kCaptureImage | od::kCaptureGroundTruth;
          }
          camera_.episode_started = false;
          camera_.steps = 0;
          image_sender_.abort();
        } else if (application) {
          Joint* j = static_cast<Joint*>(n);
          j->drive = DriveState::kSwitchOnDisabled;
          j->controlword = 0;
          j->mode = 0;
          j->target_counts = 0;
          j->ip_value = 10;
          j->ip_index = -3;
        }
        set_nmt(n, NmtState::kPreOperational);
        break;
      }
    }
  };
  if (m.node == 0) {
    for (Joint& j : joints_) apply(&j);
    apply(&camera_);
  } else if (Node* n = node(m.node)) {
    apply(n);
  }
}

uint16_t ArmNodes::statusword(const Joint& j) const {
  uint16_t sw = static_cast<uint16_t>(cia402::statusword_for(j.drive) | cia402::kSwRemote);
  if (j.drive == DriveState::kOperationEnabled && j.mode == cia402::kModeCyclicSynchronousPosition)
    sw = static_cast<uint16_t>(sw | cia402::kSwFollowingTarget | cia402::kSwTargetReached);
  return sw;
}

int32_t ArmNodes::actual_counts(int joint) const {
  int32_t counts = 0;
  angle_to_counts(world_->joint_angle_rad(joint), &counts);
  return counts;
}

void ArmNodes::on_sync() {
  ++counters_.syncs;
  if (camera_.episode_started && camera_.steps < kStepsPerEpisode) {
    double angle_rad[kJoints];
    for (int j = 0; j < kJoints; ++j) {
      const Joint& joint = joints_[j];
      const bool follows = joint.nmt == NmtState::kOperational &&
                           joint.drive == DriveState::kOperationEnabled &&
                           joint.mode == cia402::kModeCyclicSynchronousPosition;
      angle_rad[j] = follows ? counts_to_angle(joint.target_counts) : world_->joint_angle_rad(j);
    }
    world_->step_joint_angles(angle_rad);
    ++camera_.steps;
    ++counters_.steps;
  } else {
    ++counters_.idle_syncs;
  }
  for (int j = 0; j < kJoints; ++j) {
    if (joints_[j].nmt != NmtState::kOperational) continue;
    queue(encode_joint_feedback({joints_[j].id, statusword(joints_[j]), actual_counts(j)}));
  }
}

void ArmNodes::joint_fault(Joint* j, uint16_t error_code) {
  j->drive = DriveState::kFault;
  Emergency e;
  e.node = j->id;
  e.error_code = error_code;
  e.error_register = kErrorRegisterGeneric;
  queue(encode_emcy(e));
  ++counters_.emcy_sent;
}

void ArmNodes::apply_controlword(Joint* j, uint16_t cw) {
  const uint16_t previous = j->controlword;
  j->controlword = cw;
  if (j->drive == DriveState::kFault) {
    if ((cw & cia402::kCwFaultReset) != 0 && (previous & cia402::kCwFaultReset) == 0)
      j->drive = DriveState::kSwitchOnDisabled;  // fault reset on the rising edge of bit 7
    return;
  }
  if ((cw & cia402::kCwFaultReset) != 0) return;
  const DriveState d = j->drive;
  if ((cw & 0x82) == 0x00) {  // disable voltage
    j->drive = DriveState::kSwitchOnDisabled;
  } else if ((cw & 0x86) == 0x02) {  // quick stop
    j->drive = d == DriveState::kOperationEnabled ? DriveState::kQuickStopActive
                                                  : DriveState::kSwitchOnDisabled;
  } else if ((cw & 0x87) == 0x06) {  // shutdown
    if (d == DriveState::kSwitchOnDisabled || d == DriveState::kReadyToSwitchOn ||
        d == DriveState::kSwitchedOn || d == DriveState::kOperationEnabled)
      j->drive = DriveState::kReadyToSwitchOn;
  } else if ((cw & 0x8F) == 0x07) {  // switch on / disable operation
    if (d == DriveState::kReadyToSwitchOn || d == DriveState::kOperationEnabled)
      j->drive = DriveState::kSwitchedOn;
  } else if ((cw & 0x8F) == 0x0F) {  // enable operation
    if (d == DriveState::kSwitchedOn || d == DriveState::kQuickStopActive)
      j->drive = DriveState::kOperationEnabled;
  }
}

void ArmNodes::on_joint_command(const JointCommand& c) {
  Joint* j = &joints_[c.node - kFirstJointNode];
  if (j->nmt != NmtState::kOperational) return;  // PDOs only in operational
  apply_controlword(j, c.controlword);
  if (!app::within_joint_limits(c.target_counts)) {
    ++counters_.rejected_targets;
    if (j->drive != DriveState::kFault) joint_fault(j, od::kEmcyPositionLimit);
    return;
  }
  j->target_counts = c.target_counts;
}

bool ArmNodes::sdo_joint(Joint* j, SdoMessage* m) {
  const bool write = m->kind == SdoKind::kDownloadRequest;
  auto read_only = [&]() {
    m->value = kSdoAbortReadOnly;
    return false;
  };
  auto value = [&](uint32_t v, uint8_t size) {
    m->value = v;
    m->size = size;
    return true;
  };
  switch (m->index) {
    case od::kHeartbeatProducerTime:
      if (m->subindex != 0) break;
      if (!write) return value(j->heartbeat_ms, 2);
      j->heartbeat_ms = static_cast<uint16_t>(m->value);
      j->next_heartbeat_us = bus_->now_us() + j->heartbeat_ms * 1000ull;
      return true;
    case cia402::kControlword:
      if (m->subindex != 0) break;
      if (!write) return value(j->controlword, 2);
      apply_controlword(j, static_cast<uint16_t>(m->value));
      return true;
    case cia402::kStatusword:
      if (m->subindex != 0) break;
      if (write) return read_only();
      return value(statusword(*j), 2);
    case cia402::kModesOfOperation:
      if (m->subindex != 0) break;
      if (!write) return value(static_cast<uint8_t>(j->mode), 1);
      if (static_cast<int8_t>(m->value & 0xFF) != cia402::kModeCyclicSynchronousPosition) {
        m->value = kSdoAbortValueRange;
        return false;
      }
      j->mode = cia402::kModeCyclicSynchronousPosition;
      return true;
    case cia402::kModesOfOperationDisplay:
      if (m->subindex != 0) break;
      if (write) return read_only();
      return value(static_cast<uint8_t>(j->mode), 1);
    case cia402::kPositionActualValue:
      if (m->subindex != 0) break;
      if (write) return read_only();
      return value(static_cast<uint32_t>(actual_counts(j->id - kFirstJointNode)), 4);
    case cia402::kTargetPosition: {
      if (m->subindex != 0) break;
      if (!write) return value(static_cast<uint32_t>(j->target_counts), 4);
      const auto target = static_cast<int32_t>(m->value);
      if (!app::within_joint_limits(target)) {
        ++counters_.rejected_targets;
        m->value = kSdoAbortValueRange;
        return false;
      }
      j->target_counts = target;
      return true;
    }
    case cia402::kInterpolationTimePeriod:
      if (m->subindex == od::kInterpolationPeriodValueSub) {
        if (!write) return value(j->ip_value, 1);
        j->ip_value = static_cast<uint8_t>(m->value);
        return true;
      }
      if (m->subindex == od::kInterpolationPeriodIndexSub) {
        if (!write) return value(static_cast<uint8_t>(j->ip_index), 1);
        j->ip_index = static_cast<int8_t>(m->value & 0xFF);
        return true;
      }
      break;
    default:
      break;
  }
  m->value = kSdoAbortNoObject;
  return false;
}

bool ArmNodes::sdo_camera(SdoMessage* m) {
  const bool write = m->kind == SdoKind::kDownloadRequest;
  auto value = [&](uint32_t v, uint8_t size) {
    m->value = v;
    m->size = size;
    return true;
  };
  switch (m->index) {
    case od::kHeartbeatProducerTime:
      if (m->subindex != 0) break;
      if (!write) return value(camera_.heartbeat_ms, 2);
      camera_.heartbeat_ms = static_cast<uint16_t>(m->value);
      camera_.next_heartbeat_us = bus_->now_us() + camera_.heartbeat_ms * 1000ull;
      return true;
    case od::kEpisodeControl:
      if (m->subindex != od::kEpisodeStartSub) break;
      if (!write) return value(camera_.episode, 4);
      if (camera_.episode_started && m->value == camera_.episode) {
        world_->replay_episode();
        ++counters_.replays;
      } else {
        world_->reset();
      }
      image_sender_.abort();
      camera_.episode = m->value;
      camera_.episode_started = true;
      camera_.steps = 0;
      ++counters_.episodes;
      return true;
    case od::kCaptureContent:
      if (m->subindex != 0) break;
      if (!write) return value(camera_.capture_content, 1);
      if ((m->value & ~uint32_t{od::kCaptureImage | od::kCaptureGroundTruth}) != 0) {
        m->value = kSdoAbortValueRange;
        return false;
      }
      camera_.capture_content = static_cast<uint8_t>(m->value);
      return true;
    case od::kSimulatorPhysics:
      if (m->subindex != 0) break;
      if (write) {
        m->value = kSdoAbortReadOnly;
        return false;
      }
      return value(options_.physics == Physics::kOde ? od::kPhysicsOde : od::kPhysicsKinematic, 1);
    default:
      break;
  }
  m->value = kSdoAbortNoObject;
  return false;
}

void ArmNodes::on_sdo(const SdoMessage& request) {
  if (request.kind != SdoKind::kDownloadRequest && request.kind != SdoKind::kUploadRequest)
    return;  // client aborts need no answer
  Node* n = node(request.node);
  if (n == nullptr || n->nmt == NmtState::kStopped || n->nmt == NmtState::kBootUp) return;
  ++counters_.sdo_requests;
  SdoMessage m = request;
  const bool ok = n == &camera_ ? sdo_camera(&m) : sdo_joint(static_cast<Joint*>(n), &m);
  SdoMessage response;
  response.node = request.node;
  response.index = request.index;
  response.subindex = request.subindex;
  if (!ok) {
    response.kind = SdoKind::kNodeAbort;
    response.value = m.value;
    ++counters_.sdo_aborts;
  } else if (request.kind == SdoKind::kDownloadRequest) {
    response.kind = SdoKind::kDownloadResponse;
    response.value = 0;
  } else {
    response.kind = SdoKind::kUploadResponse;
    response.value = m.value;
    response.size = m.size;
  }
  queue(encode_sdo(response));
}

void ArmNodes::on_capture(const CameraCapture& c) {
  if (camera_.nmt != NmtState::kOperational) return;
  if (!camera_.episode_started || c.episode != camera_.episode) {
    ++counters_.stale_captures;
    return;
  }
  ++counters_.captures;
  const SceneState& s = world_->state();
  if ((camera_.capture_content & od::kCaptureGroundTruth) != 0) {
    GroundTruth g;
    g.episode = camera_.episode;
    g.ball_grasped = s.grasped;
    g.ball_x = s.ball.x;
    g.ball_y = s.ball.y;
    g.distractor_x = s.distractor.x;
    g.distractor_y = s.distractor.y;
    queue(encode_ground_truth(g));
  }
  if ((camera_.capture_content & od::kCaptureImage) != 0) {
    render_scene(s.ball, s.distractor, image_.get());
    to_camera_frame(*image_, frame_.get());
    image_sender_.abort();
    if (image_sender_.start(frame_->data(), frame_->size(), bus_->now_us()) !=
        IsoTpStatus::kInProgress)
      ++counters_.image_errors;
    pump_image(bus_->now_us());
  }
}

void ArmNodes::pump_image(uint64_t now) {
  while (image_sender_.busy()) {
    IsoTpReply r;
    const IsoTpStatus s = image_sender_.poll(now, &r);
    if (r.valid) queue(r.frame);
    if (s == IsoTpStatus::kComplete) {
      ++counters_.images_sent;
      return;
    }
    if (s != IsoTpStatus::kInProgress) {
      ++counters_.image_errors;
      return;
    }
    if (!r.valid) return;  // waiting for flow control or STmin
  }
}

}  // namespace curio::sim::serve
