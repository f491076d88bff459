#include "sim/serve/arm_nodes.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

#include "firmware/app/joint_target.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "sim/world_identity.hpp"

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

// A frame the camera node sends, or one addressed to it (SDO request, capture, flow control).
bool camera_node_frame(const CanFrame& f) {
  uint8_t node = 0;
  switch (classify(f, &node)) {
    case MessageKind::kGroundTruth:
    case MessageKind::kCameraImage:
    case MessageKind::kCameraCapture:
    case MessageKind::kCameraFlowControl:
      return true;
    case MessageKind::kHeartbeat:
    case MessageKind::kEmcy:
    case MessageKind::kSdoResponse:
    case MessageKind::kSdoRequest:
      return node == kCameraNode;
    default:
      return false;
  }
}

}  // namespace

ArmNodes::ArmNodes(hal::CanBus* bus, const ServeOptions& options)
    : bus_(bus),
      options_(options),
      world_(make_world(options.physics, options.world, world_seed_for_run(options.seed))),
      image_(std::make_unique<Image>()),
      frame_(std::make_unique<CameraFrame>()),
      image_sender_(camera_link_for_camera(profile_for(bus->carries_fd()))),
      sync_timing_(options.period_us),
      start_us_(bus->now_us()) {
  if (options.joint_speed_limit_rad_s > 0)
    world_->set_joint_speed_limit(options.joint_speed_limit_rad_s);
  // Power-on: every node announces itself (boot-up) and enters pre-operational.
  nodes_.power_on(app::kJointLimitCounts, &io_);
  nodes_.camera.physics =
      options.physics == Physics::kOde ? od::kPhysicsOde : od::kPhysicsKinematic;
  // Episode n's world is positioned by (seed, n) (World::reset_to_episode): 0x2000.2 says so,
  // 0x2003 tells the controller which world (a serve started with another seed, grasp radius,
  // ... is refused).
  nodes_.camera.profile = profile_for(bus->carries_fd());
  nodes_.camera.episode_indexed = true;
  nodes_.camera.has_world = true;
  nodes_.camera.world = world_identity(options.physics, options.world, options.seed);
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
    case Event::kCaptureTaken:
      ++nodes_->counters_.captures;
      return;
    case Event::kCaptureStale:
      ++nodes_->counters_.stale_captures;
      return;
    case Event::kSdoRequest:
      ++nodes_->counters_.sdo_requests;
      return;
    case Event::kSdoAbort:
      ++nodes_->counters_.sdo_aborts;
      return;
    case Event::kSdoIgnored:
      return;
    case Event::kHeartbeatMissed:
      ++nodes_->counters_.heartbeats_missed;
      return;
    case Event::kTargetLimited:
      ++nodes_->counters_.limited_targets;
      return;
    case Event::kFollowingError:
      ++nodes_->counters_.following_errors;
      return;
  }
}

void ArmNodes::queue(const CanFrame& f) {
  if (!options_.camera_node && camera_node_frame(f)) return;  // node 0x20 is not on the bus
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

uint64_t ArmNodes::next_due_us(uint64_t now) const {
  uint64_t next = nodes_.next_heartbeat_due_us();
  if (next_ramp_us_ != 0) next = std::min(next, next_ramp_us_);
  if (image_sender_.busy()) next = std::min(next, std::max(now, image_sender_.next_event_us()));
  return next;
}

void ArmNodes::timers_due(uint64_t now) {
  bool missed_before[kJointNodes];
  for (int j = 0; j < kJointNodes; ++j) missed_before[j] = nodes_.joints[j].consumer.missed();
  nodes_.heartbeats_due(now, &io_);
  for (int j = 0; j < kJointNodes; ++j) {
    const JointNode& jn = nodes_.joints[j];
    if (missed_before[j] || !jn.consumer.missed()) continue;
    events_[j].missed_us = now;
    if (options_.log != nullptr) {
      std::fprintf(options_.log,
                   "curio-sim serve: %.3f s: joint %d: heartbeat of node %u missed (none for %u "
                   "ms), EMCY 0x8130; abort connection option %d: %s\n",
                   static_cast<double>(now - start_us_) * 1e-6, j + 1, jn.consumer.producer(),
                   jn.consumer.time_ms(), jn.drive.abort_connection,
                   cia402::to_string(jn.drive.state));
    }
  }
  note_ramp_starts(now);
}

void ArmNodes::note_ramp_starts(uint64_t now) {
  for (int j = 0; j < kJointNodes; ++j) {
    const bool ramping = nodes_.joints[j].ramping();
    if (ramping && !was_ramping_[j]) events_[j].ramp_from_us = now;
    was_ramping_[j] = ramping;
  }
  if (nodes_.any_ramping()) {
    if (next_ramp_us_ == 0) {
      // The drives' period (0x60C2; all joints are told the same one).
      uint64_t period = nodes_.joints[0].drive.period_us();
      next_ramp_us_ = now + (period > 0 ? period : 10'000);
    }
  } else {
    next_ramp_us_ = 0;
  }
}

void ArmNodes::ramp_due(uint64_t now) {
  if (next_ramp_us_ == 0 || now < next_ramp_us_) return;
  double actual_rad[kJointNodes], angle_rad[kJointNodes];
  bool stood_still[kJointNodes];
  for (int j = 0; j < kJointNodes; ++j) actual_rad[j] = world_->joint_angle_rad(j);
  nodes_.ramp_period(actual_rad, angle_rad, stood_still);
  world_->step_joint_angles(angle_rad);
  ++counters_.ramp_steps;
  after_world_step();
  for (int j = 0; j < kJointNodes; ++j) {
    if (!stood_still[j]) continue;
    JointEvents& e = events_[j];
    e.standstill_us = now;
    e.standstill_rad = world_->joint_angle_rad(j);
    if (options_.log == nullptr) continue;
    const uint64_t from =
        e.missed_us != 0 && e.missed_us <= e.ramp_from_us ? e.missed_us : e.ramp_from_us;
    std::fprintf(options_.log,
                 "curio-sim serve: %.3f s: joint %d: stood still at %+.6f rad, %.1f ms after %s; "
                 "%s\n",
                 static_cast<double>(now - start_us_) * 1e-6, j + 1, e.standstill_rad,
                 static_cast<double>(now - from) / 1000.0,
                 from == e.missed_us ? "the missed heartbeat" : "its quick stop began",
                 cia402::to_string(nodes_.joints[j].drive.state));
  }
  // The drive's own clock: one step per period; after a stall it goes on from now (no burst).
  const uint64_t period =
      nodes_.joints[0].drive.period_us() > 0 ? nodes_.joints[0].drive.period_us() : 10'000;
  next_ramp_us_ = next_ramp_us_ + period > now ? next_ramp_us_ + period : now + period;
  note_ramp_starts(now);
}

void ArmNodes::after_world_step() {
  int32_t counts[kJointNodes];
  actual_counts(counts);
  nodes_.after_step(counts, &io_);
}

CanStatus ArmNodes::poll(uint64_t timeout_us) {
  uint64_t now = bus_->now_us();
  timers_due(now);
  ramp_due(now);
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
  timers_due(now);
  ramp_due(now);
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
  if (!options_.camera_node && camera_node_frame(f)) {  // for a node that is not on the bus
    ++counters_.foreign;
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
      if (decoded(decode_joint_command(f, &c))) nodes_.on_command(c, &io_);
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
    case MessageKind::kHeartbeat:
    case MessageKind::kForeign: {
      // Heartbeats of other nodes, the controller's among them (0x700 + 127 by default):
      // the consumers watch theirs. Anything else of other nodes is foreign.
      Heartbeat hb;
      if (decode_producer_heartbeat(f, &hb) == CodecStatus::kOk) {
        nodes_.on_heartbeat(hb, &io_);
        if (kind == MessageKind::kHeartbeat) return;
      }
      ++counters_.foreign;
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
  const NmtReset r = nodes_.on_nmt(m, &io_);
  // No camera node: the controller's recovery replays the episode it was in, whether cut short
  // or complete (a fault while it waited for the frame; between its frame and the next
  // episode's first SYNC nothing can fail), so the next SYNC starts that episode again.
  if (!options_.camera_node && nodes_.camera.episode_started) {
    nodes_.camera.episode_started = false;
    next_episode_ = nodes_.camera.episode;
  }
  if (!options_.camera_node && r == NmtReset::kApplication) next_episode_ = 0;
  if (r == NmtReset::kNone) return;
  // Resetting the camera node (application) also restarts the world from its seed: a fresh
  // run.
  if (r == NmtReset::kApplication)
    world_ = make_world(options_.physics, options_.world, world_seed_for_run(options_.seed));
  image_sender_.abort();
}

void ArmNodes::actual_counts(int32_t counts[kJointNodes]) const {
  for (int j = 0; j < kJointNodes; ++j) angle_to_counts(world_->joint_angle_rad(j), &counts[j]);
}

void ArmNodes::on_sync() {
  ++counters_.syncs;
  CameraNode& camera = nodes_.camera;
  if (!options_.camera_node && (!camera.episode_started || camera.steps >= kStepsPerEpisode)) {
    // No camera node to start episodes: this SYNC begins the next one (or the abandoned one).
    camera.episode = next_episode_;
    camera.episode_started = true;
    camera.steps = 0;
    // As at a camera node's episode start: the arm back to its start pose within the joints'
    // speed limits, the drives holding there.
    return_to_start();
    for (JointNode& jn : nodes_.joints) jn.hold_at(0);
    world_->reset_to_episode(camera.episode);
    ++counters_.episodes;
  }
  if (camera.episode_started && camera.steps < kStepsPerEpisode) {
    if (options_.period_us > 0) sync_timing_.on_step(camera.steps, bus_->now_us());
    double angle_rad[kJoints];
    for (int j = 0; j < kJoints; ++j)
      angle_rad[j] = nodes_.joints[j].angle_at_sync_rad(world_->joint_angle_rad(j), &io_);
    world_->step_joint_angles(angle_rad);
    ++camera.steps;
    if (!options_.camera_node && camera.steps == kStepsPerEpisode) next_episode_ = camera.episode + 1;
    ++counters_.steps;
    after_world_step();
  } else {
    ++counters_.idle_syncs;
  }
  int32_t counts[kJointNodes];
  actual_counts(counts);
  nodes_.send_feedback(counts, &io_);
  note_ramp_starts(bus_->now_us());
}

void ArmNodes::on_sdo(const SdoMessage& request) {
  int32_t counts[kJointNodes];
  actual_counts(counts);
  CameraNode::EpisodeStart start = CameraNode::EpisodeStart::kNone;
  SdoMessage answer;
  if (!nodes_.on_sdo(request, counts, &io_, &start, &answer)) return;
  if (start != CameraNode::EpisodeStart::kNone) {
    // The download response comes after the world's reset (arm_objects.hpp). Episode n's
    // randomness is positioned by its number: a replay, or the first episode after this
    // process restarted mid-run, is the same episode as in an undisturbed run.
    if (start == CameraNode::EpisodeStart::kReplay) ++counters_.replays;
    return_to_start();
    world_->reset_to_episode(nodes_.camera.episode);
    image_sender_.abort();
    ++counters_.episodes;
  }
  queue(encode_sdo(answer));
}

void ArmNodes::return_to_start() {
  // Each joint at most its speed limit (the lower of 0x607F and 0x6080) per period.
  double max_step_rad[kJointNodes];
  for (int j = 0; j < kJointNodes; ++j) {
    const JointNode& jn = nodes_.joints[j];
    const int64_t step = cia402::max_step_counts(jn.limits().max_velocity, jn.drive.period_us());
    max_step_rad[j] = static_cast<double>(step) * 1e-6;
  }
  counters_.return_steps += static_cast<uint64_t>(world_->return_to_start(max_step_rad));
}

void ArmNodes::on_capture(const CameraCapture& c) {
  if (!nodes_.camera.on_capture(c, &io_)) return;
  const SceneState& s = world_->state();
  if ((nodes_.camera.capture_content & od::kCaptureGroundTruth) != 0) {
    CanFrame truth[kGroundTruthClassicFrames];
    const size_t n = nodes_.camera.ground_truth(s.grasped, s.ball.x, s.ball.y, s.distractor.x,
                                                s.distractor.y, truth);
    for (size_t i = 0; i < n; ++i) queue(truth[i]);
  }
  if ((nodes_.camera.capture_content & od::kCaptureImage) != 0) {
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
