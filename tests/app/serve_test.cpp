// The simulated arm's nodes (sim/serve, `curio-sim serve`) seen from the bus, one frame
// exchange at a time: boot-up, NMT, SDO server, CiA 402 state machine, lockstep SYNC, RPDO
// range check with EMCY, camera capture (ground truth + ISO-TP frame), replay, reset.
#include <gtest/gtest.h>

#include <vector>

#include "firmware/protocol/arm_objects.hpp"
#include "firmware/app/joint_target.hpp"
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
  EXPECT_EQ(r.value, kSdoAbortValueRange) << "targets outside the joint range are refused";
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

TEST(ArmNodes, OutOfRangeTargetRaisesEmcyAndFaultAndIsNotApplied) {
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
  const auto fb = b.cycle(ok);
  ASSERT_EQ(fb.size(), 7u);
  EXPECT_EQ(cia402::decode_state(fb[3].statusword), cia402::DriveState::kFault);
  EXPECT_EQ(fb[3].actual_counts, 0) << "the faulted joint holds its angle";
  // Fault reset (rising edge of bit 7), then the enable sequence again.
  b.sdo(4, SdoKind::kDownloadRequest, cia402::kControlword, 0, cia402::kCwFaultReset, 2);
  EXPECT_EQ(cia402::decode_state(b.statusword(4)), cia402::DriveState::kSwitchOnDisabled);
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

}  // namespace curio::sim::serve
