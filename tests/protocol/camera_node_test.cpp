// The camera node (firmware/protocol/camera_node.hpp): episode start and replay, capture
// content with and without an image sensor, the physics object, capture requests, resets.
#include <gtest/gtest.h>

#include "firmware/protocol/camera_node.hpp"
#include "tests/protocol/node_test_io.hpp"

using namespace curio::protocol;
using curio::protocol::test::RecordingIo;
using curio::protocol::test::sdo_request;
using Start = CameraNode::EpisodeStart;

namespace {}  // namespace

TEST(CameraNode, EpisodeStartNewOrReplay) {
  RecordingIo io;
  CameraNode c;
  Start start = Start::kReplay;
  SdoMessage m = sdo_request(SdoKind::kDownloadRequest, kCameraNode, od::kEpisodeControl,
                             od::kEpisodeStartSub, 0);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(start, Start::kNew) << "episode 0 before any start is new";
  EXPECT_TRUE(c.episode_started);
  c.steps = 50;
  m = sdo_request(SdoKind::kDownloadRequest, kCameraNode, od::kEpisodeControl, od::kEpisodeStartSub,
                  0);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(start, Start::kReplay);
  EXPECT_EQ(c.steps, 0);
  m = sdo_request(SdoKind::kDownloadRequest, kCameraNode, od::kEpisodeControl, od::kEpisodeStartSub,
                  1);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(start, Start::kNew);
  EXPECT_EQ(c.episode, 1u);
  m = sdo_request(SdoKind::kUploadRequest, kCameraNode, od::kEpisodeControl, od::kEpisodeStartSub);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(start, Start::kNone);
  EXPECT_EQ(m.value, 1u);
  m = sdo_request(SdoKind::kDownloadRequest, kCameraNode, od::kEpisodeControl, 0, 2);
  EXPECT_FALSE(c.sdo(&m, &io, &start));
  EXPECT_EQ(start, Start::kNone);
  EXPECT_EQ(m.value, kSdoAbortReadOnly) << "0x2000.0, the highest sub-index, is read-only";
  m = sdo_request(SdoKind::kUploadRequest, kCameraNode, od::kEpisodeControl, 3);
  EXPECT_FALSE(c.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, kSdoAbortNoSubindex);
}

TEST(CameraNode, CaptureContentWithAndWithoutImageSensor) {
  RecordingIo io;
  Start start = Start::kNone;
  CameraNode c;
  EXPECT_EQ(c.capture_content, 0x03);
  for (const uint32_t v : {0u, 1u, 2u, 3u}) {
    SdoMessage m = sdo_request(SdoKind::kDownloadRequest, kCameraNode, od::kCaptureContent, 0, v);
    EXPECT_TRUE(c.sdo(&m, &io, &start)) << v;
    EXPECT_EQ(c.capture_content, v);
  }
  SdoMessage m = sdo_request(SdoKind::kDownloadRequest, kCameraNode, od::kCaptureContent, 0, 4);
  EXPECT_FALSE(c.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, kSdoAbortValueRange);

  CameraNode blind;
  blind.image_sensor = false;
  for (const uint32_t v : {0u, 1u, 3u}) {
    m = sdo_request(SdoKind::kDownloadRequest, kCameraNode, od::kCaptureContent, 0, v);
    EXPECT_FALSE(blind.sdo(&m, &io, &start)) << v;
    EXPECT_EQ(m.value, kSdoAbortValueRange);
  }
  m = sdo_request(SdoKind::kDownloadRequest, kCameraNode, od::kCaptureContent, 0,
                  od::kCaptureGroundTruth);
  EXPECT_TRUE(blind.sdo(&m, &io, &start));
  m = sdo_request(SdoKind::kUploadRequest, kCameraNode, od::kCaptureContent, 0);
  ASSERT_TRUE(blind.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, od::kCaptureGroundTruth);
  EXPECT_EQ(m.size, 1);
}

TEST(CameraNode, PhysicsIsReadOnlyAndHeartbeatIsServed) {
  RecordingIo io;
  Start start = Start::kNone;
  CameraNode c;
  c.physics = od::kPhysicsOde;
  SdoMessage m = sdo_request(SdoKind::kUploadRequest, kCameraNode, od::kSimulatorPhysics, 0);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, od::kPhysicsOde);
  m = sdo_request(SdoKind::kDownloadRequest, kCameraNode, od::kSimulatorPhysics, 0, 0);
  EXPECT_FALSE(c.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, kSdoAbortReadOnly);
  m = sdo_request(SdoKind::kDownloadRequest, kCameraNode, od::kHeartbeatProducerTime, 0, 30);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(c.heartbeat_ms, 30);
  m = sdo_request(SdoKind::kUploadRequest, kCameraNode, 0x6041, 0);
  EXPECT_FALSE(c.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, kSdoAbortNoObject);
}

TEST(CameraNode, CaptureRequestsAndResets) {
  RecordingIo io;
  CameraNode c;
  c.id = kCameraNode;
  c.set_nmt(NmtState::kPreOperational, &io);
  io.clear();
  EXPECT_FALSE(c.on_capture({0}, &io)) << "pre-operational";
  EXPECT_TRUE(io.events.empty()) << "ignored, not counted";
  c.set_nmt(NmtState::kOperational, &io);
  EXPECT_FALSE(c.on_capture({0}, &io)) << "no episode started";
  c.episode_started = true;
  c.episode = 4;
  EXPECT_FALSE(c.on_capture({3}, &io));
  EXPECT_EQ(io.count_of(NodeIo::Event::kCaptureStale), 2u);
  EXPECT_TRUE(c.on_capture({4}, &io));
  EXPECT_EQ(io.count_of(NodeIo::Event::kCaptureTaken), 1u);
  EXPECT_TRUE(io.frames.empty());

  // The ground truth in the node's profile: one FD frame, or five classic ones.
  for (const CanProfile profile : {CanProfile::kFd, CanProfile::kClassic}) {
    c.profile = profile;
    CanFrame frames[kGroundTruthClassicFrames];
    const size_t n = c.ground_truth(true, 0.5, -0.25, 0.7, -0.45, frames);
    ASSERT_EQ(n, profile == CanProfile::kFd ? 1u : kGroundTruthClassicFrames);
    GroundTruthAssembler a;
    GroundTruth g;
    bool complete = false;
    for (size_t i = 0; i < n; ++i) {
      EXPECT_EQ(frames[i].fd(), profile == CanProfile::kFd);
      ASSERT_EQ(a.on_frame(frames[i], &g, &complete), CodecStatus::kOk);
    }
    ASSERT_TRUE(complete);
    EXPECT_EQ(g.episode, 4u);
    EXPECT_TRUE(g.ball_grasped);
    EXPECT_EQ(g.ball_x, 0.5);
    EXPECT_EQ(g.ball_y, -0.25);
    EXPECT_EQ(g.distractor_x, 0.7);
    EXPECT_EQ(g.distractor_y, -0.45);
  }

  c.capture_content = od::kCaptureGroundTruth;
  c.steps = 9;
  c.reset(NmtReset::kNone);
  EXPECT_TRUE(c.episode_started);
  c.reset(NmtReset::kCommunication);
  EXPECT_FALSE(c.episode_started);
  EXPECT_EQ(c.steps, 0);
  EXPECT_EQ(c.capture_content, od::kCaptureGroundTruth);
  c.reset(NmtReset::kApplication);
  EXPECT_EQ(c.capture_content, CameraNode::kDefaultCaptureContent);
}
