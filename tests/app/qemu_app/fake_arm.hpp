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
// Node behaviour follows sim/serve/arm_nodes.cpp (the simulated arm of curio-sim serve)
// reduced to what the controller uses. Firmware-clean: no heap, no OS, static storage.
#pragma once
#include <cmath>
#include <cstdint>

#include "firmware/protocol/arm_objects.hpp"
#include "firmware/app/joint_target.hpp"
#include "firmware/explore/prng.hpp"
#include "hal/frame_queue.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/cia402.hpp"

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
    if (noise_std != 0.0) {
      const double wx = noise_std * walk.prng.normal();
      const double wy = noise_std * walk.prng.normal();
      walk.x = clamp(walk.x + wx);
      walk.y = clamp(walk.y + wy);
    }
  }
  static double clamp(double v) {
    return v < -kDistractorBound ? -kDistractorBound : (kDistractorBound < v ? kDistractorBound : v);
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
    seed_ = run_seed;
    grasp_radius_ = grasp_radius;
    noise_ = distractor_noise;
    world_.create(seed_, grasp_radius_, noise_);
    for (int j = 0; j < protocol::kJointNodes; ++j) {
      joints_[j] = Joint{};
      joints_[j].id = static_cast<uint8_t>(protocol::kFirstJointNode + j);
    }
    camera_ = Camera{};
    camera_.id = protocol::kCameraNode;
    for (Joint& j : joints_) set_nmt(&j, protocol::NmtState::kPreOperational, 0);
    set_nmt(&camera_, protocol::NmtState::kPreOperational, 0);
  }

  // Heartbeats that are due at `now`.
  void tick(uint64_t now) {
    for (Joint& j : joints_) heartbeat_due(&j, now);
    heartbeat_due(&camera_, now);
  }

  // One frame from the bus (the controller's); answers go to the out queue at once.
  void handle(const hal::CanFrame& f, uint64_t now) {
    using namespace protocol;
    uint8_t id = 0;
    switch (classify(f, &id)) {
      case MessageKind::kNmt: {
        NmtMessage m;
        if (decode_nmt(f, &m) == CodecStatus::kOk) on_nmt(m, now);
        return;
      }
      case MessageKind::kSync: {
        uint8_t counter = 0;
        if (decode_sync(f, &counter) == CodecStatus::kOk) on_sync();
        return;
      }
      case MessageKind::kJointCommand: {
        JointCommand c;
        if (decode_joint_command(f, &c) == CodecStatus::kOk) on_joint_command(c);
        return;
      }
      case MessageKind::kSdoRequest: {
        SdoMessage m;
        if (decode_sdo(f, &m) == CodecStatus::kOk) on_sdo(m, now);
        return;
      }
      case MessageKind::kCameraCapture: {
        CameraCapture c;
        if (decode_camera_capture(f, &c) == CodecStatus::kOk) on_capture(c);
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
  struct Node {
    uint8_t id = 0;
    protocol::NmtState nmt = protocol::NmtState::kBootUp;
    uint16_t heartbeat_ms = 0;
    uint64_t next_heartbeat_us = 0;
  };
  struct Joint : Node {
    protocol::cia402::DriveState drive = protocol::cia402::DriveState::kSwitchOnDisabled;
    uint16_t controlword = 0;
    int8_t mode = 0;
    int32_t target_counts = 0;
    uint8_t ip_value = 10;
    int8_t ip_index = -3;
  };
  struct Camera : Node {
    uint8_t capture_content = protocol::od::kCaptureImage | protocol::od::kCaptureGroundTruth;
    bool episode_started = false;
    uint32_t episode = 0;
    int steps = 0;
  };

  void queue(const hal::CanFrame& f) {
    if (!out_->push(f)) ++counters_.dropped;
  }

  void send_heartbeat(Node* n, uint64_t now) {
    queue(protocol::encode_heartbeat({n->id, n->nmt}));
    ++counters_.heartbeats;
    if (n->heartbeat_ms > 0) n->next_heartbeat_us = now + n->heartbeat_ms * 1000ull;
  }

  void heartbeat_due(Node* n, uint64_t now) {
    if (n->heartbeat_ms == 0 || n->nmt == protocol::NmtState::kBootUp || now < n->next_heartbeat_us)
      return;
    send_heartbeat(n, now);
  }

  void set_nmt(Node* n, protocol::NmtState state, uint64_t now) {
    using protocol::NmtState;
    if (state == NmtState::kPreOperational && n->nmt == NmtState::kBootUp) {
      queue(protocol::encode_heartbeat({n->id, NmtState::kBootUp}));  // boot-up (CiA 301)
      ++counters_.heartbeats;
    }
    const bool changed = n->nmt != state;
    n->nmt = state;
    if (changed && n->heartbeat_ms > 0) send_heartbeat(n, now);
  }

  void on_nmt(const protocol::NmtMessage& m, uint64_t now) {
    using namespace protocol;
    auto apply = [&](Node* n) {
      switch (m.command) {
        case NmtCommand::kStart:
          set_nmt(n, NmtState::kOperational, now);
          break;
        case NmtCommand::kStop:
          set_nmt(n, NmtState::kStopped, now);
          break;
        case NmtCommand::kEnterPreOperational:
          set_nmt(n, NmtState::kPreOperational, now);
          break;
        case NmtCommand::kResetNode:
        case NmtCommand::kResetCommunication: {
          const bool application = m.command == NmtCommand::kResetNode;
          n->heartbeat_ms = 0;
          n->nmt = NmtState::kBootUp;
          if (n == &camera_) {
            if (application) {  // a fresh run: the world from its seed
              world_.create(seed_, grasp_radius_, noise_);
              camera_.capture_content = protocol::od::kCaptureImage | protocol::od::kCaptureGroundTruth;
            }
            camera_.episode_started = false;
            camera_.steps = 0;
          } else if (application) {
            Joint* j = static_cast<Joint*>(n);
            const uint8_t id = j->id;
            *j = Joint{};
            j->id = id;
          }
          set_nmt(n, NmtState::kPreOperational, now);
          break;
        }
      }
    };
    if (m.node == 0) {
      for (Joint& j : joints_) apply(&j);
      apply(&camera_);
    } else if (protocol::is_joint_node(m.node)) {
      apply(&joints_[m.node - protocol::kFirstJointNode]);
    } else if (m.node == protocol::kCameraNode) {
      apply(&camera_);
    }
  }

  static uint16_t statusword(const Joint& j) {
    using namespace protocol::cia402;
    auto sw = static_cast<uint16_t>(statusword_for(j.drive) | kSwRemote);
    if (j.drive == DriveState::kOperationEnabled && j.mode == kModeCyclicSynchronousPosition)
      sw = static_cast<uint16_t>(sw | kSwFollowingTarget | kSwTargetReached);
    return sw;
  }

  int32_t actual_counts(int joint) const {
    int32_t counts = 0;
    protocol::angle_to_counts(world_.angle_rad[joint], &counts);
    return counts;
  }

  void on_sync() {
    using namespace protocol;
    if (camera_.episode_started && camera_.steps < kStepsPerEpisode) {
      double angle_rad[kJoints];
      for (int j = 0; j < kJoints; ++j) {
        const Joint& joint = joints_[j];
        const bool follows = joint.nmt == NmtState::kOperational &&
                             joint.drive == cia402::DriveState::kOperationEnabled &&
                             joint.mode == cia402::kModeCyclicSynchronousPosition;
        angle_rad[j] = follows ? counts_to_angle(joint.target_counts) : world_.angle_rad[j];
      }
      world_.step(angle_rad);
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

  void apply_controlword(Joint* j, uint16_t cw) {
    using protocol::cia402::DriveState;
    using protocol::cia402::kCwFaultReset;
    const uint16_t previous = j->controlword;
    j->controlword = cw;
    if (j->drive == DriveState::kFault) {
      if ((cw & kCwFaultReset) != 0 && (previous & kCwFaultReset) == 0)
        j->drive = DriveState::kSwitchOnDisabled;
      return;
    }
    if ((cw & kCwFaultReset) != 0) return;
    const DriveState d = j->drive;
    if ((cw & 0x82) == 0x00) {
      j->drive = DriveState::kSwitchOnDisabled;
    } else if ((cw & 0x86) == 0x02) {
      j->drive = d == DriveState::kOperationEnabled ? DriveState::kQuickStopActive
                                                    : DriveState::kSwitchOnDisabled;
    } else if ((cw & 0x87) == 0x06) {
      if (d == DriveState::kSwitchOnDisabled || d == DriveState::kReadyToSwitchOn ||
          d == DriveState::kSwitchedOn || d == DriveState::kOperationEnabled)
        j->drive = DriveState::kReadyToSwitchOn;
    } else if ((cw & 0x8F) == 0x07) {
      if (d == DriveState::kReadyToSwitchOn || d == DriveState::kOperationEnabled)
        j->drive = DriveState::kSwitchedOn;
    } else if ((cw & 0x8F) == 0x0F) {
      if (d == DriveState::kSwitchedOn || d == DriveState::kQuickStopActive)
        j->drive = DriveState::kOperationEnabled;
    }
  }

  void on_joint_command(const protocol::JointCommand& c) {
    Joint* j = &joints_[c.node - protocol::kFirstJointNode];
    if (j->nmt != protocol::NmtState::kOperational) return;
    apply_controlword(j, c.controlword);
    if (!app::within_joint_limits(c.target_counts)) {
      ++counters_.rejected_targets;
      if (j->drive != protocol::cia402::DriveState::kFault) {
        j->drive = protocol::cia402::DriveState::kFault;
        protocol::Emergency e;
        e.node = j->id;
        e.error_code = protocol::od::kEmcyPositionLimit;
        e.error_register = 0x01;
        queue(protocol::encode_emcy(e));
      }
      return;
    }
    j->target_counts = c.target_counts;
  }

  // false: abort code in m->value.
  bool sdo_joint(Joint* j, protocol::SdoMessage* m, uint64_t now) {
    using namespace protocol;
    const bool write = m->kind == SdoKind::kDownloadRequest;
    auto value = [&](uint32_t v, uint8_t size) {
      m->value = v;
      m->size = size;
      return true;
    };
    auto abort = [&](uint32_t code) {
      m->value = code;
      return false;
    };
    switch (m->index) {
      case protocol::od::kHeartbeatProducerTime:
        if (m->subindex != 0) break;
        if (!write) return value(j->heartbeat_ms, 2);
        j->heartbeat_ms = static_cast<uint16_t>(m->value);
        j->next_heartbeat_us = now + j->heartbeat_ms * 1000ull;
        return true;
      case cia402::kControlword:
        if (m->subindex != 0) break;
        if (!write) return value(j->controlword, 2);
        apply_controlword(j, static_cast<uint16_t>(m->value));
        return true;
      case cia402::kStatusword:
        if (m->subindex != 0) break;
        if (write) return abort(kSdoAbortReadOnly);
        return value(statusword(*j), 2);
      case cia402::kModesOfOperation:
        if (m->subindex != 0) break;
        if (!write) return value(static_cast<uint8_t>(j->mode), 1);
        if (static_cast<int8_t>(m->value & 0xFF) != cia402::kModeCyclicSynchronousPosition)
          return abort(kSdoAbortValueRange);
        j->mode = cia402::kModeCyclicSynchronousPosition;
        return true;
      case cia402::kInterpolationTimePeriod:
        if (m->subindex == protocol::od::kInterpolationPeriodValueSub) {
          if (!write) return value(j->ip_value, 1);
          j->ip_value = static_cast<uint8_t>(m->value);
          return true;
        }
        if (m->subindex == protocol::od::kInterpolationPeriodIndexSub) {
          if (!write) return value(static_cast<uint8_t>(j->ip_index), 1);
          j->ip_index = static_cast<int8_t>(m->value & 0xFF);
          return true;
        }
        break;
      default:
        break;
    }
    return abort(kSdoAbortNoObject);
  }

  bool sdo_camera(protocol::SdoMessage* m, uint64_t now) {
    using namespace protocol;
    namespace od = protocol::od;
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
        camera_.next_heartbeat_us = now + camera_.heartbeat_ms * 1000ull;
        return true;
      case od::kEpisodeControl:
        if (m->subindex != od::kEpisodeStartSub) break;
        if (!write) return value(camera_.episode, 4);
        if (camera_.episode_started && m->value == camera_.episode) {
          world_.replay();
          ++counters_.replays;
        } else {
          world_.reset();
        }
        camera_.episode = m->value;
        camera_.episode_started = true;
        camera_.steps = 0;
        ++counters_.episodes;
        return true;
      case od::kCaptureContent:
        if (m->subindex != 0) break;
        if (!write) return value(camera_.capture_content, 1);
        // This camera has no image sensor: only the ground truth can be captured.
        if (m->value != od::kCaptureGroundTruth) {
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
        return value(od::kPhysicsKinematic, 1);
      default:
        break;
    }
    m->value = kSdoAbortNoObject;
    return false;
  }

  void on_sdo(const protocol::SdoMessage& request, uint64_t now) {
    using namespace protocol;
    if (request.kind != SdoKind::kDownloadRequest && request.kind != SdoKind::kUploadRequest)
      return;
    Node* n = nullptr;
    if (is_joint_node(request.node))
      n = &joints_[request.node - kFirstJointNode];
    else if (request.node == kCameraNode)
      n = &camera_;
    if (n == nullptr || n->nmt == NmtState::kStopped || n->nmt == NmtState::kBootUp) {
      ++counters_.ignored;
      return;
    }
    ++counters_.sdo_requests;
    SdoMessage m = request;
    const bool ok =
        n == &camera_ ? sdo_camera(&m, now) : sdo_joint(static_cast<Joint*>(n), &m, now);
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

  void on_capture(const protocol::CameraCapture& c) {
    if (camera_.nmt != protocol::NmtState::kOperational) return;
    if (!camera_.episode_started || c.episode != camera_.episode) {
      ++counters_.ignored;
      return;
    }
    ++counters_.captures;
    if ((camera_.capture_content & protocol::od::kCaptureGroundTruth) == 0) return;
    protocol::GroundTruth g;
    g.episode = camera_.episode;
    g.ball_grasped = world_.grasped;
    g.ball_x = world_.ball_x;
    g.ball_y = world_.ball_y;
    g.distractor_x = world_.walk.x;
    g.distractor_y = world_.walk.y;
    queue(protocol::encode_ground_truth(g));
  }

  OutQueue* out_ = nullptr;
  uint64_t seed_ = 0;
  double grasp_radius_ = 0.1;
  double noise_ = 0.1;
  KinematicArm2Balls world_;
  Joint joints_[protocol::kJointNodes];
  Camera camera_;
  Counters counters_;
};

}  // namespace curio::test
