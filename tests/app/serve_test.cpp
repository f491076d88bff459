// The simulated arm's nodes (sim/serve, `curio-sim serve`) seen from the bus, one frame
// exchange at a time: boot-up, NMT, SDO server, CiA 402 state machine, lockstep SYNC, RPDO
// range check with EMCY, camera capture (ground truth + ISO-TP frame), replay, reset.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "firmware/protocol/arm_objects.hpp"
#include "firmware/app/joint_target.hpp"
#include "hal/clock.hpp"
#include "hal/host/loopback_bus.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "sim/camera.hpp"
#include "sim/serve/arm_nodes.hpp"

namespace curio::sim::serve {
namespace {

using hal::CanFrame;
using namespace protocol;
namespace od = protocol::od;

// A master endpoint and the node set on one loopback wire, polled cooperatively.
// `fd` false: both ends classic-only (the classic profile).
struct Bench {
  std::shared_ptr<hal::LoopbackBus> wire = hal::LoopbackBus::create();
  std::unique_ptr<hal::LoopbackEndpoint> master;
  std::unique_ptr<hal::LoopbackEndpoint> arm_end;
  ArmNodes nodes;
  explicit Bench(Physics physics = Physics::kKinematic, uint64_t seed = 4, bool fd = true)
      : master(wire->open(fd)),
        arm_end(wire->open(fd)),
        nodes(arm_end.get(), ServeOptions{physics, {}, seed}) {}

  // Sends `frames`, lets the nodes handle them, returns what they answered.
  std::vector<CanFrame> exchange(const std::vector<CanFrame>& frames) {
    if (!frames.empty()) {
      EXPECT_EQ(
          master->send_batch(frames.data(), frames.size(), master->now_us() + 100'000, nullptr),
          hal::CanStatus::kOk);
    }
    for (int i = 0; i < 4; ++i) nodes.poll(0);
    std::vector<CanFrame> got;
    CanFrame batch[64];
    size_t n = 0;
    while (master->receive_batch(batch, 64, &n) == hal::CanStatus::kOk)
      got.insert(got.end(), batch, batch + n);
    return got;
  }
  std::vector<CanFrame> exchange(const CanFrame& f) { return exchange(std::vector<CanFrame>{f}); }

  // One SDO transfer: the answer (asserts there is exactly one).
  SdoMessage sdo(uint8_t node, SdoKind kind, uint16_t index, uint8_t sub, uint32_t value = 0,
                 uint8_t size = 4) {
    SdoMessage m;
    m.kind = kind;
    m.node = node;
    m.index = index;
    m.subindex = sub;
    m.value = value;
    m.size = size;
    const auto got = exchange(encode_sdo(m));
    SdoMessage answer;
    int answers = 0;
    for (const CanFrame& f : got) {
      SdoMessage r;
      if (decode_sdo(f, &r) == CodecStatus::kOk && r.node == node) {
        answer = r;
        ++answers;
      }
    }
    EXPECT_EQ(answers, 1) << "SDO 0x" << std::hex << index << " to node " << std::dec << int(node);
    return answer;
  }
  uint16_t statusword(uint8_t node) {
    return static_cast<uint16_t>(sdo(node, SdoKind::kUploadRequest, cia402::kStatusword, 0).value);
  }
  void start_and_enable() {
    exchange(encode_nmt({NmtCommand::kStart, 0}));
    for (uint8_t n = 1; n <= 7; ++n) {
      sdo(n, SdoKind::kDownloadRequest, cia402::kModesOfOperation, 0, 8, 1);
      for (uint16_t cw : {cia402::kCwShutdown, cia402::kCwSwitchOn, cia402::kCwEnableOperation})
        sdo(n, SdoKind::kDownloadRequest, cia402::kControlword, 0, cw, 2);
    }
  }
  // One SYNC cycle with all joints at `counts`; returns the 7 feedbacks.
  std::vector<JointFeedback> cycle(const int32_t counts[7]) {
    std::vector<CanFrame> frames;
    for (uint8_t n = 1; n <= 7; ++n)
      frames.push_back(encode_joint_command({n, cia402::kCwEnableOperation, counts[n - 1]}));
    frames.push_back(encode_sync(1));
    std::vector<JointFeedback> fb;
    for (const CanFrame& f : exchange(frames)) {
      JointFeedback j;
      if (decode_joint_feedback(f, &j) == CodecStatus::kOk) fb.push_back(j);
    }
    return fb;
  }
  GroundTruth capture(uint32_t episode) {
    GroundTruth g;
    int n = 0;
    for (const CanFrame& f : exchange(encode_camera_capture({episode})))
      if (decode_ground_truth(f, &g) == CodecStatus::kOk) ++n;
    EXPECT_EQ(n, 1);
    return g;
  }
  void start_episode(uint32_t episode) {
    EXPECT_EQ(sdo(kCameraNode, SdoKind::kDownloadRequest, od::kEpisodeControl, od::kEpisodeStartSub,
                  episode)
                  .kind,
              SdoKind::kDownloadResponse);
  }
};

TEST(ArmNodes, BootUpHeartbeatsFromAllEightNodes) {
  auto wire = hal::LoopbackBus::create();
  auto master = wire->open();
  auto arm_end = wire->open();
  ArmNodes nodes(arm_end.get(), {});
  CanFrame batch[16];
  size_t n = 0;
  ASSERT_EQ(master->receive_batch(batch, 16, &n), hal::CanStatus::kOk);
  ASSERT_EQ(n, 8u);
  for (size_t i = 0; i < n; ++i) {
    Heartbeat hb;
    ASSERT_EQ(decode_heartbeat(batch[i], &hb), CodecStatus::kOk);
    EXPECT_EQ(hb.state, NmtState::kBootUp);
    EXPECT_TRUE(is_curio_node(hb.node));
  }
}

TEST(ArmNodes, SdoServerAnswersAndRefusesAsCanopenSays) {
  Bench b(Physics::kOde);
  EXPECT_EQ(b.sdo(kCameraNode, SdoKind::kUploadRequest, od::kSimulatorPhysics, 0).value,
            od::kPhysicsOde);
  SdoMessage r = b.sdo(3, SdoKind::kDownloadRequest, cia402::kModesOfOperation, 0, 7, 1);
  EXPECT_EQ(r.kind, SdoKind::kNodeAbort);
  EXPECT_EQ(r.value, kSdoAbortValueRange) << "only cyclic synchronous position (8)";
  r = b.sdo(3, SdoKind::kDownloadRequest, cia402::kStatusword, 0, 0, 2);
  EXPECT_EQ(r.value, kSdoAbortReadOnly);
  r = b.sdo(3, SdoKind::kUploadRequest, 0x1234, 0);
  EXPECT_EQ(r.value, kSdoAbortNoObject);
  r = b.sdo(3, SdoKind::kDownloadRequest, cia402::kTargetPosition, 0,
            static_cast<uint32_t>(app::kJointLimitCounts + 1));
  EXPECT_EQ(r.kind, SdoKind::kDownloadResponse) << "targets outside 0x607D are clamped";
  EXPECT_EQ(b.sdo(3, SdoKind::kUploadRequest, cia402::kTargetPosition, 0).value,
            static_cast<uint32_t>(app::kJointLimitCounts));
  r = b.sdo(3, SdoKind::kUploadRequest, cia402::kTargetPosition, 1);
  EXPECT_EQ(r.value, kSdoAbortNoSubindex);
  EXPECT_EQ(b.sdo(3, SdoKind::kUploadRequest, od::kDeviceType, 0).value, od::kDeviceTypeServoDrive);
  EXPECT_EQ(b.sdo(kCameraNode, SdoKind::kUploadRequest, od::kIdentity, 0).value, 4u);
  EXPECT_EQ(b.sdo(3, SdoKind::kDownloadRequest, od::kHeartbeatProducerTime, 0, 100, 2).kind,
            SdoKind::kDownloadResponse);
  EXPECT_EQ(b.sdo(3, SdoKind::kUploadRequest, od::kHeartbeatProducerTime, 0).value, 100u);
  // Stopped nodes do not serve SDO.
  b.exchange(encode_nmt({NmtCommand::kStop, 3}));
  SdoMessage m;
  m.kind = SdoKind::kUploadRequest;
  m.node = 3;
  m.index = cia402::kStatusword;
  bool answered = false;
  for (const CanFrame& f : b.exchange(encode_sdo(m))) answered |= f.id == kCobSdoResponse + 3;
  EXPECT_FALSE(answered);
}

TEST(ArmNodes, Cia402StateMachine) {
  using cia402::DriveState;
  Bench b;
  b.exchange(encode_nmt({NmtCommand::kStart, 0}));
  EXPECT_EQ(cia402::decode_state(b.statusword(1)), DriveState::kSwitchOnDisabled);
  b.sdo(1, SdoKind::kDownloadRequest, cia402::kControlword, 0, cia402::kCwEnableOperation, 2);
  EXPECT_EQ(cia402::decode_state(b.statusword(1)), DriveState::kSwitchOnDisabled) << "no shortcut";
  b.sdo(1, SdoKind::kDownloadRequest, cia402::kControlword, 0, cia402::kCwShutdown, 2);
  EXPECT_EQ(cia402::decode_state(b.statusword(1)), DriveState::kReadyToSwitchOn);
  b.sdo(1, SdoKind::kDownloadRequest, cia402::kControlword, 0, cia402::kCwSwitchOn, 2);
  EXPECT_EQ(cia402::decode_state(b.statusword(1)), DriveState::kSwitchedOn);
  b.sdo(1, SdoKind::kDownloadRequest, cia402::kControlword, 0, cia402::kCwEnableOperation, 2);
  EXPECT_EQ(cia402::decode_state(b.statusword(1)), DriveState::kOperationEnabled);
  b.sdo(1, SdoKind::kDownloadRequest, cia402::kControlword, 0, cia402::kCwDisableVoltage, 2);
  EXPECT_EQ(cia402::decode_state(b.statusword(1)), DriveState::kSwitchOnDisabled);
}

TEST(ArmNodes, WorldStepsOncePerSyncDuringAnEpisodeOnly) {
  Bench b;
  b.start_and_enable();
  int32_t counts[7] = {100000, -200000, 300000, 0, 0, 0, 3141593};
  auto fb = b.cycle(counts);  // before any episode: no step
  ASSERT_EQ(fb.size(), 7u);
  EXPECT_EQ(b.nodes.counters().steps, 0u);
  EXPECT_EQ(b.nodes.counters().idle_syncs, 1u);
  b.start_episode(0);
  for (int t = 0; t < kStepsPerEpisode; ++t) {
    fb = b.cycle(counts);
    ASSERT_EQ(fb.size(), 7u);
    for (const JointFeedback& j : fb) {
      EXPECT_EQ(j.actual_counts, counts[j.node - 1]) << "kinematic joints land on the target";
      EXPECT_EQ(cia402::decode_state(j.statusword), cia402::DriveState::kOperationEnabled);
    }
  }
  EXPECT_EQ(b.nodes.counters().steps, 50u);
  b.cycle(counts);  // a 51st SYNC does not move the world
  EXPECT_EQ(b.nodes.counters().steps, 50u);
  EXPECT_EQ(b.nodes.counters().idle_syncs, 2u);
}

TEST(ArmNodes, OutOfRangeTargetIsClampedAndReportedOnce) {
  Bench b;
  b.start_and_enable();
  b.start_episode(0);
  const int32_t ok[7] = {1000, 0, 0, 0, 0, 0, 0};
  b.cycle(ok);
  const auto got = b.exchange(
      encode_joint_command({4, cia402::kCwEnableOperation, -app::kJointLimitCounts - 1}));
  Emergency e;
  ASSERT_EQ(got.size(), 1u);
  ASSERT_EQ(decode_emcy(got[0], &e), CodecStatus::kOk);
  EXPECT_EQ(e.node, 4);
  EXPECT_EQ(e.error_code, od::kEmcyPositionLimit);
  const int32_t beyond[7] = {1000, 0, 0, -app::kJointLimitCounts - 1, 0, 0, 0};
  const auto fb = b.cycle(beyond);
  ASSERT_EQ(fb.size(), 7u) << "no second EMCY for the same excursion";
  EXPECT_EQ(cia402::decode_state(fb[3].statusword), cia402::DriveState::kOperationEnabled);
  EXPECT_EQ(fb[3].actual_counts, -app::kJointLimitCounts) << "clamped to the limit";
  EXPECT_EQ(b.nodes.counters().rejected_targets, 2u);
  EXPECT_EQ(b.nodes.counters().emcy_sent, 1u);
}

// Both profiles: the same ground truth and the same image bytes, in FD or classic frames.
class ArmNodesProfile : public ::testing::TestWithParam<CanProfile> {};

TEST_P(ArmNodesProfile, CaptureSendsGroundTruthAndTheRenderedFrame) {
  const CanProfile profile = GetParam();
  Bench b(Physics::kKinematic, 4, profile == CanProfile::kFd);
  b.start_and_enable();
  b.start_episode(7);
  int32_t counts[7] = {};
  for (int t = 0; t < kStepsPerEpisode; ++t) {
    for (int j = 0; j < 7; ++j) counts[j] = (t * 12345 * (j + 1)) % 2000000 - 1000000;
    b.cycle(counts);
  }
  const SceneState& s = b.nodes.world().state();
  // Ground truth first, then the image over ISO-TP (the master answers the flow control).
  std::vector<uint8_t> image(kIsoTpMaxMessage);
  IsoTpReceiver rx(camera_link_for_controller(profile), image.data(), image.size());
  GroundTruthAssembler truth;
  GroundTruth g;
  bool have_gt = false, complete = false;
  size_t truth_frames = 0, image_frames = 0;
  std::vector<CanFrame> got = b.exchange(encode_camera_capture({7}));
  for (int round = 0; round < 10 && !complete; ++round) {
    std::vector<CanFrame> replies;
    for (const CanFrame& f : got) {
      EXPECT_TRUE(profile == CanProfile::kFd || !f.fd()) << "an FD frame in the classic profile";
      bool whole = false;
      if (truth.on_frame(f, &g, &whole) == CodecStatus::kOk) {
        ++truth_frames;
        have_gt = have_gt || whole;
      }
      if (f.id == kCameraImageId) ++image_frames;
      IsoTpReply r;
      if (rx.on_frame(f, 0, &r) == IsoTpStatus::kComplete) complete = true;
      if (r.valid) replies.push_back(r.frame);
    }
    got = b.exchange(replies);
  }
  ASSERT_TRUE(have_gt);
  EXPECT_EQ(g.episode, 7u);
  EXPECT_EQ(g.ball_x, s.ball.x);
  EXPECT_EQ(g.ball_y, s.ball.y);
  EXPECT_EQ(g.distractor_x, s.distractor.x);
  EXPECT_EQ(g.distractor_y, s.distractor.y);
  EXPECT_EQ(g.ball_grasped, s.grasped);
  ASSERT_TRUE(complete);
  Image rendered;
  CameraFrame frame;
  render_scene(s.ball, s.distractor, &rendered);
  to_camera_frame(rendered, &frame);
  EXPECT_TRUE(std::equal(frame.begin(), frame.end(), image.begin()));
  // One FD frame or five classic ones. The image: a first frame with the 32-bit length escape
  // (6 PCI bytes) and consecutive frames of 63 (FD, 64-byte) or 7 (classic) bytes:
  // FD 58 + 195 × 63 ≥ 12,288 → 196 frames; classic 2 + 1,756 × 7 ≥ 12,288 → 1,757 frames.
  const bool fd = profile == CanProfile::kFd;
  EXPECT_EQ(truth_frames, fd ? 1u : kGroundTruthClassicFrames);
  EXPECT_EQ(image_frames, fd ? 196u : 1757u);
  // A capture for another episode is ignored.
  EXPECT_TRUE(b.exchange(encode_camera_capture({8})).empty());
  EXPECT_EQ(b.nodes.counters().stale_captures, 1u);
}

INSTANTIATE_TEST_SUITE_P(Profiles, ArmNodesProfile,
                         ::testing::Values(CanProfile::kFd, CanProfile::kClassic),
                         [](const auto& info) { return std::string(to_string(info.param)); });

// The same episode number again replays the episode (retries); a new number continues the
// distractor's stream; NMT reset of the camera node restarts the world from its seed.
TEST(ArmNodes, ReplayAndResetAreDeterministic) {
  Bench b(Physics::kOde, 9);
  b.start_and_enable();
  const int32_t counts[7] = {500000, 250000, -100000, 0, 0, 0, 0};
  auto episode = [&](uint32_t n) {
    b.start_episode(n);
    for (int t = 0; t < kStepsPerEpisode; ++t) b.cycle(counts);
    return b.capture(n);
  };
  const GroundTruth first = episode(0);
  const GroundTruth again = episode(0);
  const GroundTruth next = episode(1);
  EXPECT_EQ(first.distractor_x, again.distractor_x);
  EXPECT_EQ(first.distractor_y, again.distractor_y);
  EXPECT_EQ(first.ball_x, again.ball_x);
  EXPECT_NE(first.distractor_x, next.distractor_x);
  EXPECT_EQ(b.nodes.counters().replays, 1u);
  b.exchange(encode_nmt({NmtCommand::kResetNode, kCameraNode}));
  b.exchange(encode_nmt({NmtCommand::kStart, kCameraNode}));
  const GroundTruth fresh = episode(0);
  EXPECT_EQ(fresh.distractor_x, first.distractor_x);
  EXPECT_EQ(fresh.distractor_y, first.distractor_y);
}

TEST(ArmNodes, MalformedAndForeignFramesAreCountedAndIgnored) {
  Bench b;
  b.start_and_enable();
  CanFrame bad_rpdo = encode_joint_command({2, cia402::kCwEnableOperation, 5});
  bad_rpdo.len = 5;
  CanFrame foreign = encode_joint_command({2, cia402::kCwEnableOperation, 5});
  foreign.id = kCobRpdo1 + 0x30;
  CanFrame fd_sync = encode_sync(1);
  fd_sync.flags = hal::kFlagFd;
  EXPECT_TRUE(b.exchange({bad_rpdo, foreign, fd_sync}).empty());
  EXPECT_EQ(b.nodes.counters().malformed, 2u);
  EXPECT_EQ(b.nodes.counters().foreign, 1u);
  EXPECT_EQ(b.nodes.counters().syncs, 0u);
}

}  // namespace
// The drives' view of the controller's clock: intervals between the SYNCs of an episode only
// (the pause before an episode is not a period), late and early against the period.
TEST(SyncTiming, MeasuresTheIntervalsOfEachEpisodeAgainstThePeriod) {
  SyncTiming t(10'000);
  for (const auto& [step, us] : std::vector<std::pair<int, uint64_t>>{
           {0, 0}, {1, 10'000}, {2, 20'000}, {3, 35'001}, {4, 39'000},  // late, then early
           {0, 1'000'000}, {1, 1'010'000}}) {
    t.on_step(step, us);
  }
  const SyncTiming::Summary s = t.summary();
  EXPECT_EQ(s.intervals, 5u);
  EXPECT_EQ(s.p50_us, 10'000);
  EXPECT_EQ(s.max_us, 15'001);
  EXPECT_EQ(s.late, 1u);
  EXPECT_EQ(s.early, 1u);
}

// ---- The drives' safety reactions, on the serve's own clock (a manual one: no waiting).

namespace {

// The nodes on a loopback wire whose time moves only when told.
struct ClockedBench {
  hal::ManualClock clock{1'000'000};
  std::shared_ptr<hal::LoopbackBus> wire = hal::LoopbackBus::create(&clock);
  std::unique_ptr<hal::LoopbackEndpoint> master = wire->open(true);
  std::unique_ptr<hal::LoopbackEndpoint> arm_end = wire->open(true);
  char* log_text = nullptr;
  size_t log_size = 0;
  std::FILE* log = open_memstream(&log_text, &log_size);
  ArmNodes nodes;
  std::vector<CanFrame> received;  // everything the nodes sent, in order
  std::vector<uint64_t> received_at;

  explicit ClockedBench(Physics physics, double speed_limit = 0)
      : nodes(arm_end.get(), options(physics, log, speed_limit)) {}
  ~ClockedBench() {
    std::fclose(log);
    std::free(log_text);
  }
  static ServeOptions options(Physics physics, std::FILE* log, double speed_limit) {
    ServeOptions o{physics, {}, 4};
    o.log = log;
    o.joint_speed_limit_rad_s = speed_limit;
    return o;
  }
  std::string log_lines() {
    std::fflush(log);
    return std::string(log_text, log_size);
  }
  void send(const std::vector<CanFrame>& frames) {
    ASSERT_EQ(master->send_batch(frames.data(), frames.size(), master->now_us() + 100'000, nullptr),
              hal::CanStatus::kOk);
  }
  // Lets the nodes handle what was sent; collects their frames.
  void settle() {
    for (int i = 0; i < 4; ++i) nodes.poll(0);
    CanFrame batch[64];
    size_t n = 0;
    while (master->receive_batch(batch, 64, &n) == hal::CanStatus::kOk) {
      for (size_t i = 0; i < n; ++i) {
        received.push_back(batch[i]);
        received_at.push_back(clock.now_us());
      }
    }
  }
  void sdo_write(uint8_t node, uint16_t index, uint8_t sub, uint32_t value) {
    const size_t before = received.size();
    send({encode_sdo({SdoKind::kDownloadRequest, node, index, sub, value, 4})});
    settle();
    bool answered = false;
    for (size_t i = before; i < received.size(); ++i) {
      SdoMessage r;
      if (decode_sdo(received[i], &r) == CodecStatus::kOk && r.node == node) {
        EXPECT_EQ(r.kind, SdoKind::kDownloadResponse)
            << std::hex << "0x" << index << "." << int(sub) << " abort 0x" << r.value;
        answered = true;
      }
    }
    EXPECT_TRUE(answered);
  }
  void heartbeat() {
    send({encode_heartbeat({od::kDefaultMasterNode, NmtState::kOperational})});
    settle();
  }
  // The consumer time these tests configure (the controller's default is longer): short, so
  // that the silences below stay short.
  static constexpr uint16_t kBenchConsumerTimeMs = 200;
  // Configures every joint as Curio's controller does, starts and enables them, starts
  // episode 0.
  void configure_and_enable() {
    send({encode_nmt({NmtCommand::kStart, 0})});
    settle();
    for (uint8_t n = 1; n <= 7; ++n) {
      sdo_write(n, od::kConsumerHeartbeatTime, 1,
                od::consumer_heartbeat_entry(od::kDefaultMasterNode, kBenchConsumerTimeMs));
      sdo_write(n, od::kAbortConnectionOption, 0, od::kConfigAbortConnection);
      sdo_write(n, od::kQuickStopOptionCode, 0, od::kConfigQuickStopOption);
      sdo_write(n, od::kFaultReactionOptionCode, 0, od::kConfigFaultReaction);
      sdo_write(n, od::kQuickStopDeceleration, 0, od::kConfigQuickStopDecelCounts);
      sdo_write(n, od::kMaxProfileVelocity, 0, od::kConfigMaxVelocityCounts);
      sdo_write(n, od::kFollowingErrorWindow, 0, od::kConfigFollowingErrorWindow);
      sdo_write(n, od::kFollowingErrorTimeOut, 0, od::kConfigFollowingErrorTimeOutMs);
      sdo_write(n, cia402::kModesOfOperation, 0, 8);
      for (uint16_t cw : {cia402::kCwShutdown, cia402::kCwSwitchOn, cia402::kCwEnableOperation})
        sdo_write(n, cia402::kControlword, 0, cw);
    }
    sdo_write(kCameraNode, od::kEpisodeControl, od::kEpisodeStartSub, 0);
  }
  // One control period: targets and SYNC, then 10 ms later (`in_ms_steps`: the nodes polled
  // every 1 ms of it).
  void cycle(const int32_t counts[7], bool in_ms_steps = false) {
    std::vector<CanFrame> frames;
    for (uint8_t n = 1; n <= 7; ++n)
      frames.push_back(encode_joint_command({n, cia402::kCwEnableOperation, counts[n - 1]}));
    frames.push_back(encode_sync(1));
    send(frames);
    settle();
    for (int ms = 0; ms < 10; ++ms) {
      clock.advance_us(1'000);
      if (in_ms_steps) settle();
    }
  }
};

// The controller dies in the middle of a motion: it sends no heartbeat and no SYNC any more.
// Each joint holds its last target (CSP: no new target), misses the heartbeat after the
// consumer time, sends EMCY 0x8130, quick-stops (at rest already: standstill in the first
// period of its own clock) and ends in switch on disabled; the serve logs each joint's miss and
// standstill.
TEST(ArmNodesSafety, SilentControllerEveryJointSendsEmcyAndStandsStill) {
  for (const Physics physics : {Physics::kKinematic, Physics::kOde}) {
    SCOPED_TRACE(physics_name(physics));
    ClockedBench b(physics);
    b.configure_and_enable();
    // Moving at 20 rad/s (0.2 rad per period), joint j in direction (−1)^j.
    int32_t counts[7] = {};
    for (int t = 1; t <= 5; ++t) {
      b.heartbeat();
      for (int j = 0; j < 7; ++j) counts[j] = (j % 2 == 0 ? 1 : -1) * 200'000 * t;
      b.cycle(counts);
    }
    const uint64_t last_heartbeat = b.clock.now_us() - 10'000;
    const size_t before = b.received.size();
    // Silence: 1 ms steps of the serve's clock, for 0.5 s.
    for (int ms = 0; ms < 500; ++ms) {
      b.clock.advance_us(1'000);
      b.settle();
    }
    int emcy_8130 = 0;
    uint64_t last_emcy = 0;
    for (size_t i = before; i < b.received.size(); ++i) {
      Emergency e;
      if (decode_emcy(b.received[i], &e) != CodecStatus::kOk) continue;
      EXPECT_EQ(e.error_code, od::kEmcyHeartbeatLost);
      EXPECT_EQ(e.error_register & od::kErrorRegisterCommunication,
                od::kErrorRegisterCommunication);
      ++emcy_8130;
      last_emcy = b.received_at[i];
    }
    EXPECT_EQ(emcy_8130, 7) << "one EMCY 0x8130 per joint";
    EXPECT_GT(last_emcy, last_heartbeat + ClockedBench::kBenchConsumerTimeMs * 1000);
    EXPECT_LE(last_emcy, last_heartbeat + ClockedBench::kBenchConsumerTimeMs * 1000 + 2'000);
    for (int j = 0; j < 7; ++j) {
      SCOPED_TRACE(j + 1);
      const ArmNodes::JointEvents& e = b.nodes.joint_events(j);
      EXPECT_EQ(b.nodes.drive_state(j), cia402::DriveState::kSwitchOnDisabled);
      ASSERT_NE(e.missed_us, 0u);
      ASSERT_NE(e.standstill_us, 0u);
      // The consumer time, then one period of the drive's clock (1 ms steps here).
      EXPECT_LE(e.standstill_us - last_heartbeat,
                ClockedBench::kBenchConsumerTimeMs * 1000u + 10'000u + 2'000u);
      // Where its last target put it, and it holds there.
      EXPECT_NEAR(e.standstill_rad, counts[j] * 1e-6, 1e-9);
      EXPECT_NEAR(b.nodes.world().joint_angle_rad(j), e.standstill_rad, 1e-9) << "stands still";
    }
    EXPECT_EQ(b.nodes.counters().heartbeats_missed, 7u);
    EXPECT_GT(b.nodes.counters().ramp_steps, 0u);
    const std::string log = b.log_lines();
    for (int j = 1; j <= 7; ++j) {
      const std::string joint = "joint " + std::to_string(j) + ": ";
      EXPECT_NE(log.find(joint + "heartbeat of node 127 missed"), std::string::npos) << log;
      EXPECT_NE(log.find(joint + "stood still at"), std::string::npos) << log;
    }
  }
}

// The controller's heartbeat is lost while its targets and SYNCs still come (its heartbeat
// thread died, or the bus drops 0x77F): each joint is moving when it misses the heartbeat, so
// the quick stop decelerates it on 0x6085 to standstill, and the targets that keep coming
// (controlword 0x000F) do not take it out of the quick stop (0x605A = 2).
TEST(ArmNodesSafety, HeartbeatLostWhileTargetsStillComeRampsToStandstill) {
  for (const Physics physics : {Physics::kKinematic, Physics::kOde}) {
    SCOPED_TRACE(physics_name(physics));
    ClockedBench b(physics);
    b.configure_and_enable();
    for (uint8_t n = 1; n <= 7; ++n)
      b.sdo_write(n, od::kQuickStopDeceleration, 0, 100'000'000);  // 100 rad/s²
    b.heartbeat();
    const uint64_t last_heartbeat = b.clock.now_us();
    int32_t counts[7] = {};
    int32_t at_miss[7] = {};
    for (int t = 1; t <= 30; ++t) {  // 2 rad/s, 300 ms: the miss comes at the 21st period
      for (int j = 0; j < 7; ++j) counts[j] = -20'000 * t;
      const bool missed_before = b.nodes.counters().heartbeats_missed > 0;
      b.cycle(counts, /*in_ms_steps=*/true);
      if (!missed_before && b.nodes.counters().heartbeats_missed > 0) {
        for (int j = 0; j < 7; ++j) at_miss[j] = counts[j];
      }
    }
    ASSERT_EQ(b.nodes.counters().heartbeats_missed, 7u);
    for (int j = 0; j < 7; ++j) {
      SCOPED_TRACE(j + 1);
      const ArmNodes::JointEvents& e = b.nodes.joint_events(j);
      EXPECT_EQ(b.nodes.drive_state(j), cia402::DriveState::kSwitchOnDisabled);
      EXPECT_GT(e.missed_us, last_heartbeat + ClockedBench::kBenchConsumerTimeMs * 1000u);
      // 2 rad/s at 100 rad/s²: 20 ms of ramp (two periods), v²/2a = 0.02 rad past the last
      // target it took.
      EXPECT_LE(e.standstill_us - e.missed_us, 20'000u + 10'000u + 1'000u);
      EXPECT_NEAR(e.standstill_rad, at_miss[j] * 1e-6 - 0.02, 1e-6);
      EXPECT_NEAR(b.nodes.world().joint_angle_rad(j), e.standstill_rad, 1e-9);
    }
  }
}

// The controller's own quick stop (controlword 0x0002) while it still sends SYNCs: the ramp runs
// on the serve's clock, the SYNCs do not move the ramping joints, and the drives end in switch on
// disabled.
TEST(ArmNodesSafety, ControlwordQuickStopRampsInTheDrivesTimeWithOrWithoutSync) {
  ClockedBench b(Physics::kKinematic);
  b.configure_and_enable();
  int32_t counts[7] = {};
  for (int t = 1; t <= 3; ++t) {
    b.heartbeat();
    for (int j = 0; j < 7; ++j) counts[j] = 100'000 * t;  // 10 rad/s
    b.cycle(counts);
  }
  std::vector<CanFrame> stop;
  for (uint8_t n = 1; n <= 7; ++n)
    stop.push_back(encode_joint_command({n, cia402::kCwQuickStop, counts[n - 1]}));
  b.send(stop);
  b.settle();
  for (int j = 0; j < 7; ++j) {
    EXPECT_EQ(b.nodes.drive_state(j), cia402::DriveState::kQuickStopActive);
  }
  for (int ms = 0; ms < 40; ++ms) {
    b.heartbeat();
    if (ms % 10 == 0) {
      b.send({encode_sync(1)});  // SYNCs still come
      b.settle();
    }
    b.clock.advance_us(1'000);
  }
  for (int j = 0; j < 7; ++j) {
    EXPECT_EQ(b.nodes.drive_state(j), cia402::DriveState::kSwitchOnDisabled);
    // 10 rad/s at 1000 rad/s²: 0.05 rad beyond the last target.
    EXPECT_NEAR(b.nodes.world().joint_angle_rad(j), 0.3 + 0.05, 1e-6);
  }
  EXPECT_EQ(b.nodes.counters().heartbeats_missed, 0u);
  EXPECT_NE(b.log_lines().find("after its quick stop began"), std::string::npos);
}

// A joint that cannot keep up (the ODE arm with a motor speed limit) leaves the following
// error window: EMCY 0x8611, the fault reaction's ramp, Fault.
TEST(ArmNodesSafety, OdeJointThatLagsRaisesFollowingErrorAndFaults) {
  ClockedBench b(Physics::kOde, /*speed_limit=*/5.0);  // 0.05 rad per period at most
  b.configure_and_enable();
  int32_t counts[7] = {};
  const size_t before = b.received.size();
  for (int t = 1; t <= 6; ++t) {
    b.heartbeat();
    counts[2] = 200'000 * t;  // joint 3 told 20 rad/s
    b.cycle(counts);
  }
  for (int ms = 0; ms < 50; ++ms) {
    b.heartbeat();
    b.clock.advance_us(1'000);
  }
  int following = 0;
  for (size_t i = before; i < b.received.size(); ++i) {
    Emergency e;
    if (decode_emcy(b.received[i], &e) != CodecStatus::kOk) continue;
    EXPECT_EQ(e.node, 3);
    EXPECT_EQ(e.error_code, od::kEmcyFollowingError);
    ++following;
  }
  EXPECT_EQ(following, 1);
  EXPECT_EQ(b.nodes.drive_state(2), cia402::DriveState::kFault);
  EXPECT_EQ(b.nodes.counters().following_errors, 1u);
  for (int j = 0; j < 7; ++j) {
    if (j != 2) {
      EXPECT_EQ(b.nodes.drive_state(j), cia402::DriveState::kOperationEnabled);
    }
  }
}

// The ODE arm returns to its start pose between episodes within the joints' speed limit, and
// the episode after it is the same as after the instant reset.
TEST(ArmNodesSafety, OdeArmReturnsToItsStartPoseWithinTheSpeedLimit) {
  ClockedBench limited(Physics::kOde), instant(Physics::kOde);
  limited.configure_and_enable();
  instant.configure_and_enable();
  for (uint8_t n = 1; n <= 7; ++n)
    limited.sdo_write(n, od::kMaxProfileVelocity, 0, 10'000'000);  // 10 rad/s: 0.1 rad/period
  int32_t counts[7] = {};
  for (int t = 1; t <= 10; ++t) {
    for (int j = 0; j < 7; ++j) counts[j] = 90'000 * t * (j + 1) / 7;
    limited.cycle(counts);
    instant.cycle(counts);
  }
  EXPECT_NEAR(limited.nodes.world().joint_angle_rad(6), 0.9, 1e-9);
  limited.sdo_write(kCameraNode, od::kEpisodeControl, od::kEpisodeStartSub, 1);
  instant.sdo_write(kCameraNode, od::kEpisodeControl, od::kEpisodeStartSub, 1);
  EXPECT_EQ(limited.nodes.counters().return_steps, 9u) << "0.9 rad at 0.1 rad per period";
  EXPECT_EQ(instant.nodes.counters().return_steps, 1u);
  for (int t = 1; t <= 5; ++t) {
    for (int j = 0; j < 7; ++j) counts[j] = -50'000 * t;
    limited.cycle(counts);
    instant.cycle(counts);
  }
  for (int j = 0; j < 7; ++j) {
    EXPECT_EQ(limited.nodes.world().joint_angle_rad(j), instant.nodes.world().joint_angle_rad(j));
  }
  EXPECT_EQ(limited.nodes.world().state().hand.x, instant.nodes.world().state().hand.x);
  EXPECT_EQ(limited.nodes.world().state().distractor.y,
            instant.nodes.world().state().distractor.y);
}

}  // namespace
}  // namespace curio::sim::serve
