// A minimal in-image Arm-2-Balls arm as CAN nodes, for running the real controller
// (firmware/app) without a bus or a host: seven CiA 402 joint drives (node ids 1–7, cyclic
// synchronous position) and the camera node (0x20), answering NMT, expedited SDO, SYNC and
// RPDO1 with TPDO1, heartbeats, EMCY on out-of-range targets, and the capture request with
// the ground-truth message (no camera image: engineered features need none).
//
// The world is the kinematic model of SPEC §1.1 in double precision, written independently
// of sim/ but following it step for step (sim/kinematic_world.cpp, sim/kinematics.cpp,
// sim/grasp.hpp, sim/distractor_walk.cpp): joint angles are counts_to_angle(RPDO target),
// absolute angle = cumulative sum, hand = Σ l_j (cos, sin), strict grasp radius, then the
// distractor walk (curio::Prng(world_seed_for_run(seed), "distrac" stream), x drawn before
// y, clipped to ±0.95). Episode start (SDO 0x2000.1) resets the scene and keeps the walk's
// stream; the same episode number again rewinds the stream (replay). The host test checks
// the archive this arm produces against sim::KinematicWorld in-process.
//
// The nodes are the simulated arm's (sim/serve/arm_nodes.cpp, curio-sim serve): the shared
// firmware/protocol/joint_node.hpp and camera_node.hpp, over this world and the bus's
// virtual time. Firmware-clean: no heap, no OS, static storage.
#pragma once
#include <cmath>
#include <cstdint>

#include "firmware/app/joint_target.hpp"
#include "firmware/explore/prng.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/arm_node_set.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "hal/frame_queue.hpp"

namespace curio::test {

// ---- the world (SPEC §1.1), double precision
struct KinematicArm2Balls {
  static constexpr double kLinkLengths[kJoints] = {0.3, 0.2, 0.2, 0.1, 0.1, 0.05, 0.05};
  static constexpr double kBallStartX = 0.6, kBallStartY = 0.6;
  static constexpr double kDistractorStartX = 0.7, kDistractorStartY = -0.45;
  static constexpr double kDistractorBound = 0.95;
  static constexpr uint64_t kWalkStream = 0x64697374726163ULL;  // "distrac", as sim/

  // sim::world_seed_for_run: the world seed of a run seed.
  static constexpr uint64_t world_seed_for_run(uint64_t run_seed) {
    return run_seed * 0x9E3779B97F4A7C15ULL + 0x5EED;
  }

  struct Walk {
    Prng prng;
    double x = kDistractorStartX, y = kDistractorStartY;
  };

  double grasp_radius = 0.1;
  double noise_std = 0.1;
  Walk walk;
  Walk walk_at_episode_start;
  double angle_rad[kJoints] = {};
  double hand_x = 1.0, hand_y = 0.0;
  double ball_x = kBallStartX, ball_y = kBallStartY;
  bool grasped = false;

  void create(uint64_t run_seed, double radius, double noise) {
    grasp_radius = radius;
    noise_std = noise;
    walk = Walk{Prng(world_seed_for_run(run_seed), kWalkStream)};
    reset();
  }
  // New episode: scene to its start state, the walk's stream continues.
  void reset() {
    walk.x = kDistractorStartX;
    walk.y = kDistractorStartY;
    walk_at_episode_start = walk;
    start_episode();
  }
  // The last episode again: the walk's stream rewound to the last reset().
  void replay() {
    walk = walk_at_episode_start;
    start_episode();
  }
  void start_episode() {
    hand_x = 1.0;
    hand_y = 0.0;
    ball_x = kBallStartX;
    ball_y = kBallStartY;
    grasped = false;
    for (double& a : angle_rad) a = 0.0;
  }
  // One control period with relative joint angles (rad).
  void step(const double relative_rad[kJoints]) {
    move_joints(relative_rad);
    if (noise_std != 0.0) {
      const double wx = noise_std * walk.prng.normal();
      const double wy = noise_std * walk.prng.normal();
      walk.x = clamp(walk.x + wx);
      walk.y = clamp(walk.y + wy);
    }
  }
  // The joints to relative angles (rad), the ball carried if grasped; the distractor does not
  // move (a drive's ramp between SYNCs: the episode's random stream is not touched).
  void move_joints(const double relative_rad[kJoints]) {
    double x = 0.0, y = 0.0, absolute = 0.0;
    for (int j = 0; j < kJoints; ++j) {
      angle_rad[j] = relative_rad[j];
      absolute += relative_rad[j];
      x += kLinkLengths[j] * std::cos(absolute);
      y += kLinkLengths[j] * std::sin(absolute);
    }
    hand_x = x;
    hand_y = y;
    if (!grasped) {
      const double dx = hand_x - ball_x;
      const double dy = hand_y - ball_y;
      grasped = std::sqrt(dx * dx + dy * dy) < grasp_radius;
    }
    if (grasped) {
      ball_x = hand_x;
      ball_y = hand_y;
    }
  }
  static double clamp(double v) {
    return v < -kDistractorBound ? -kDistractorBound
                                 : (kDistractorBound < v ? kDistractorBound : v);
  }
};

// ---- the nodes
class FakeArm {
 public:
  static constexpr size_t kOutDepth = 64;
  using OutQueue = hal::FrameQueue<kOutDepth>;

  struct Counters {
    uint32_t steps = 0, idle_syncs = 0, episodes = 0, replays = 0, captures = 0;
    uint32_t sdo_requests = 0, sdo_aborts = 0, rejected_targets = 0, heartbeats = 0;
    uint32_t ignored = 0, dropped = 0;  // frames for nobody here; answers lost (queue full)
  };

  // Power-on: every node sends boot-up and enters pre-operational.
  void init(uint64_t run_seed, double grasp_radius, double distractor_noise, OutQueue* out) {
    out_ = out;
    now_ = 0;
    seed_ = run_seed;
    grasp_radius_ = grasp_radius;
    noise_ = distractor_noise;
    world_.create(seed_, grasp_radius_, noise_);
    nodes_.power_on(app::kJointLimitCounts, &io_);
    nodes_.camera.image_sensor = false;  // engineered features need only the ground truth
  }

  // Heartbeats and heartbeat consumers that are due at `now`, and one period of the joints'
  // quick stop or fault reaction ramps when it is due (the drives' own time, SYNC or not).
  void tick(uint64_t now) {
    now_ = now;
    nodes_.heartbeats_due(now, &io_);
    if (!nodes_.any_ramping()) {
      next_ramp_us_ = 0;
      return;
    }
    const uint64_t period = nodes_.joints[0].drive.period_us();
    if (next_ramp_us_ == 0) next_ramp_us_ = now + period;
    if (now < next_ramp_us_) return;
    double angle_rad[kJoints];
    bool stood_still[kJoints];
    nodes_.ramp_period(world_.angle_rad, angle_rad, stood_still);
    world_.move_joints(angle_rad);
    next_ramp_us_ = now + period;
  }

  // One frame from the bus (the controller's); answers go to the out queue at once.
  void handle(const hal::CanFrame& f, uint64_t now) {
    using namespace protocol;
    now_ = now;
    uint8_t id = 0;
    switch (classify(f, &id)) {
      case MessageKind::kNmt: {
        NmtMessage m;
        if (decode_nmt(f, &m) == CodecStatus::kOk) on_nmt(m);
        return;
      }
      case MessageKind::kSync: {
        uint8_t counter = 0;
        if (decode_sync(f, &counter) == CodecStatus::kOk) on_sync();
        return;
      }
      case MessageKind::kJointCommand: {
        JointCommand c;
        if (decode_joint_command(f, &c) == CodecStatus::kOk) nodes_.on_command(c, &io_);
        return;
      }
      case MessageKind::kSdoRequest: {
        SdoMessage m;
        if (decode_sdo(f, &m) == CodecStatus::kOk) on_sdo(m);
        return;
      }
      case MessageKind::kCameraCapture: {
        CameraCapture c;
        if (decode_camera_capture(f, &c) == CodecStatus::kOk) on_capture(c);
        return;
      }
      case MessageKind::kHeartbeat:
      case MessageKind::kForeign: {
        Heartbeat hb;  // the controller's heartbeat (0x77F by default) for the consumers
        if (decode_producer_heartbeat(f, &hb) == CodecStatus::kOk) {
          nodes_.on_heartbeat(hb, &io_);
          return;
        }
        ++counters_.ignored;
        return;
      }
      default:
        ++counters_.ignored;
        return;
    }
  }

  const Counters& counters() const { return counters_; }
  const KinematicArm2Balls& world() const { return world_; }

 private:
  // The nodes send into the out queue, count into counters_ and read the bus's time (the
  // `now` of the call being handled).
  class Io final : public protocol::NodeIo {
   public:
    explicit Io(FakeArm* arm) : arm_(arm) {}
    void send(const hal::CanFrame& f) override {
      if (!arm_->out_->push(f)) ++arm_->counters_.dropped;
    }
    void count(Event e) override {
      if (e == Event::kHeartbeatSent) ++arm_->counters_.heartbeats;
      if (e == Event::kTargetRejected) ++arm_->counters_.rejected_targets;
      if (e == Event::kCaptureTaken) ++arm_->counters_.captures;
      if (e == Event::kCaptureStale || e == Event::kSdoIgnored) ++arm_->counters_.ignored;
      if (e == Event::kSdoRequest) ++arm_->counters_.sdo_requests;
      if (e == Event::kSdoAbort) ++arm_->counters_.sdo_aborts;
    }
    uint64_t now_us() override { return arm_->now_; }

   private:
    FakeArm* arm_;
  };

  void on_nmt(const protocol::NmtMessage& m) {
    if (nodes_.on_nmt(m, &io_) == protocol::NmtReset::kApplication)
      world_.create(seed_, grasp_radius_, noise_);  // a fresh run: the world from its seed
  }

  void actual_counts(int32_t counts[protocol::kJointNodes]) const {
    for (int j = 0; j < protocol::kJointNodes; ++j)
      protocol::angle_to_counts(world_.angle_rad[j], &counts[j]);
  }

  void on_sync() {
    protocol::CameraNode& camera = nodes_.camera;
    if (camera.episode_started && camera.steps < kStepsPerEpisode) {
      double angle_rad[kJoints];
      for (int j = 0; j < kJoints; ++j)
        angle_rad[j] = nodes_.joints[j].angle_at_sync_rad(world_.angle_rad[j], &io_);
      world_.step(angle_rad);
      ++camera.steps;
      ++counters_.steps;
    } else {
      ++counters_.idle_syncs;
    }
    int32_t counts[protocol::kJointNodes];
    actual_counts(counts);
    nodes_.send_feedback(counts, &io_);
  }

  void on_sdo(const protocol::SdoMessage& request) {
    using namespace protocol;
    int32_t counts[kJointNodes];
    actual_counts(counts);
    CameraNode::EpisodeStart start = CameraNode::EpisodeStart::kNone;
    SdoMessage answer;
    if (!nodes_.on_sdo(request, counts, &io_, &start, &answer)) return;
    if (start == CameraNode::EpisodeStart::kReplay) {
      world_.replay();
      ++counters_.replays;
    } else if (start == CameraNode::EpisodeStart::kNew) {
      world_.reset();
    }
    if (start != CameraNode::EpisodeStart::kNone) ++counters_.episodes;
    io_.send(encode_sdo(answer));
  }

  void on_capture(const protocol::CameraCapture& c) {
    if (!nodes_.camera.on_capture(c, &io_)) return;
    if ((nodes_.camera.capture_content & protocol::od::kCaptureGroundTruth) == 0) return;
    hal::CanFrame truth[protocol::kGroundTruthClassicFrames];
    const size_t n = nodes_.camera.ground_truth(world_.grasped, world_.ball_x, world_.ball_y,
                                                world_.walk.x, world_.walk.y, truth);
    for (size_t i = 0; i < n; ++i) io_.send(truth[i]);
  }

  OutQueue* out_ = nullptr;
  uint64_t now_ = 0;  // the time of the call being handled
  uint64_t next_ramp_us_ = 0;  // 0: no joint ramps
  uint64_t seed_ = 0;
  double grasp_radius_ = 0.1;
  double noise_ = 0.1;
  KinematicArm2Balls world_;
  Io io_{this};
  protocol::ArmNodeSet nodes_;
  Counters counters_;
};

}  // namespace curio::test
