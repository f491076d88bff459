#include "sim/serve/arm_nodes.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

#include "firmware/app/joint_target.hpp"
#include "firmware/protocol/arm_objects.hpp"

namespace curio::sim::serve {

using hal::CanFrame;
using hal::CanStatus;
using namespace protocol;
namespace od = protocol::od;

namespace {

constexpr uint64_t kTxDeadlineUs = 100'000;
constexpr uint64_t kTickUs = 1'000;

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
  for (int j = 0; j < kJointNodes; ++j) {
    joints_[j].id = static_cast<uint8_t>(kFirstJointNode + j);
    joints_[j].limit_counts = app::kJointLimitCounts;
  }
  camera_.id = kCameraNode;
  camera_.physics = options.physics == Physics::kOde ? od::kPhysicsOde : od::kPhysicsKinematic;
  // Power-on: every node announces itself (boot-up) and enters pre-operational.
  for (JointNode& j : joints_) j.set_nmt(NmtState::kPreOperational, &io_);
  camera_.set_nmt(NmtState::kPreOperational, &io_);
  flush();
}

ArmNodes::~ArmNodes() = default;

void ArmNodes::Io::count(Event e) {
  switch (e) {
    case Event::kHeartbeatSent:
      ++nodes_->counters_.heartbeats_sent;
      return;
    case Event::kEmcySent:
      ++nodes_->counters_.emcy_sent;
      return;
    case Event::kTargetRejected:
      ++nodes_->counters_.rejected_targets;
      return;
  }
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

void ArmNodes::heartbeats_due(uint64_t now) {
  for (JointNode& j : joints_) j.heartbeat_due(now, &io_);
  camera_.heartbeat_due(now, &io_);
}

uint64_t ArmNodes::next_due_us(uint64_t now) const {
  uint64_t next = camera_.next_heartbeat_due_us();
  for (const JointNode& j : joints_) next = std::min(next, j.next_heartbeat_due_us());
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
  // A frame with one of our ids that does not decode is malformed.
  auto decoded = [&](CodecStatus s) {
    if (s != CodecStatus::kOk) ++counters_.malformed;
    return s == CodecStatus::kOk;
  };
  switch (kind) {
    case MessageKind::kNmt: {
      NmtMessage m;
      if (decoded(decode_nmt(f, &m))) on_nmt(m);
      return;
    }
    case MessageKind::kSync: {
      uint8_t counter = 0;
      if (decoded(decode_sync(f, &counter))) on_sync();
      return;
    }
    case MessageKind::kJointCommand: {
      JointCommand c;
      if (decoded(decode_joint_command(f, &c)))
        joints_[c.node - kFirstJointNode].on_command(c, &io_);
      return;
    }
    case MessageKind::kSdoRequest: {
      SdoMessage m;
      const CodecStatus s = decode_sdo(f, &m);
      if (s == CodecStatus::kUnsupported || s == CodecStatus::kBadCommand) {
        // Segmented/block transfers or unknown specifiers: refuse, as a real node would.
        SdoMessage abort;
        abort.kind = SdoKind::kNodeAbort;
        abort.node = id;
        abort.index = get_le16_index(f);
        abort.subindex = f.len >= 4 ? f.data[3] : 0;
        abort.value = kSdoAbortBadCommand;
        queue(encode_sdo(abort));
        ++counters_.sdo_aborts;
      } else if (decoded(s)) {
        on_sdo(m);
      }
      return;
    }
    case MessageKind::kCameraCapture: {
      CameraCapture c;
      if (decoded(decode_camera_capture(f, &c))) on_capture(c);
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
  auto joint = [&](JointNode* j) {
    if (j->on_nmt(m.command, &io_) == NmtReset::kApplication) j->reset_application();
  };
  auto camera = [&]() {
    const NmtReset r = camera_.on_nmt(m.command, &io_);
    if (r == NmtReset::kNone) return;
    // Resetting the camera node (application) also restarts the world from its seed: a
    // fresh run.
    if (r == NmtReset::kApplication)
      world_ = make_world(options_.physics, options_.world, world_seed_for_run(options_.seed));
    camera_.reset(r);
    image_sender_.abort();
  };
  if (m.node == 0) {
    for (JointNode& j : joints_) joint(&j);
    camera();
  } else if (is_joint_node(m.node)) {
    joint(&joints_[m.node - kFirstJointNode]);
  } else if (m.node == kCameraNode) {
    camera();
  }
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
    for (int j = 0; j < kJoints; ++j)
      angle_rad[j] = joints_[j].angle_at_sync_rad(world_->joint_angle_rad(j));
    world_->step_joint_angles(angle_rad);
    ++camera_.steps;
    ++counters_.steps;
  } else {
    ++counters_.idle_syncs;
  }
  for (int j = 0; j < kJoints; ++j) {
    if (joints_[j].nmt != NmtState::kOperational) continue;
    queue(joints_[j].feedback(actual_counts(j)));
  }
}

bool ArmNodes::sdo_camera(SdoMessage* m) {
  CameraNode::EpisodeStart start = CameraNode::EpisodeStart::kNone;
  const bool ok = camera_.sdo(m, &io_, &start);
  if (start == CameraNode::EpisodeStart::kNone) return ok;
  if (start == CameraNode::EpisodeStart::kReplay) {
    world_->replay_episode();
    ++counters_.replays;
  } else {
    world_->reset();
  }
  image_sender_.abort();
  ++counters_.episodes;
  return ok;
}

void ArmNodes::on_sdo(const SdoMessage& request) {
  if (request.kind != SdoKind::kDownloadRequest && request.kind != SdoKind::kUploadRequest)
    return;  // client aborts need no answer
  const bool joint = is_joint_node(request.node);
  const int j = request.node - kFirstJointNode;
  CanopenNode* n = nullptr;
  if (joint)
    n = &joints_[j];
  else if (request.node == kCameraNode)
    n = &camera_;
  if (n == nullptr || !n->serves_sdo()) return;
  ++counters_.sdo_requests;
  SdoMessage m = request;
  const bool ok = joint ? joints_[j].sdo(&m, actual_counts(j), &io_) : sdo_camera(&m);
  if (!ok) ++counters_.sdo_aborts;
  queue(encode_sdo(sdo_answer(request, m, ok)));
}

void ArmNodes::on_capture(const CameraCapture& c) {
  const CameraNode::Capture capture = camera_.on_capture(c);
  if (capture == CameraNode::Capture::kIgnore) return;
  if (capture == CameraNode::Capture::kStale) {
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
