// The camera node (firmware/protocol/camera_node.hpp): episode start and replay, capture
// content with and without an image sensor, the physics object, capture requests, resets.
#include <gtest/gtest.h>

#include "firmware/protocol/camera_node.hpp"
#include "tests/protocol/node_test_io.hpp"

using namespace curio::protocol;
using curio::protocol::test::RecordingIo;
using Start = CameraNode::EpisodeStart;

namespace {

SdoMessage request(SdoKind kind, uint16_t index, uint8_t sub, uint32_t value = 0) {
  SdoMessage m;
  m.kind = kind;
  m.node = kCameraNode;
  m.index = index;
  m.subindex = sub;
  m.value = value;
  return m;
}

}  // namespace

TEST(CameraNode, EpisodeStartNewOrReplay) {
  RecordingIo io;
  CameraNode c;
  Start start = Start::kReplay;
  SdoMessage m = request(SdoKind::kDownloadRequest, od::kEpisodeControl, od::kEpisodeStartSub, 0);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(start, Start::kNew) << "episode 0 before any start is new";
  EXPECT_TRUE(c.episode_started);
  c.steps = 50;
  m = request(SdoKind::kDownloadRequest, od::kEpisodeControl, od::kEpisodeStartSub, 0);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(start, Start::kReplay);
  EXPECT_EQ(c.steps, 0);
  m = request(SdoKind::kDownloadRequest, od::kEpisodeControl, od::kEpisodeStartSub, 1);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(start, Start::kNew);
  EXPECT_EQ(c.episode, 1u);
  m = request(SdoKind::kUploadRequest, od::kEpisodeControl, od::kEpisodeStartSub);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(start, Start::kNone);
  EXPECT_EQ(m.value, 1u);
  m = request(SdoKind::kDownloadRequest, od::kEpisodeControl, 0, 2);
  EXPECT_FALSE(c.sdo(&m, &io, &start));
  EXPECT_EQ(start, Start::kNone);
  EXPECT_EQ(m.value, kSdoAbortNoObject);
}

TEST(CameraNode, CaptureContentWithAndWithoutImageSensor) {
  RecordingIo io;
  Start start = Start::kNone;
  CameraNode c;
  EXPECT_EQ(c.capture_content, 0x03);
  for (const uint32_t v : {0u, 1u, 2u, 3u}) {
    SdoMessage m = request(SdoKind::kDownloadRequest, od::kCaptureContent, 0, v);
    EXPECT_TRUE(c.sdo(&m, &io, &start)) << v;
    EXPECT_EQ(c.capture_content, v);
  }
  SdoMessage m = request(SdoKind::kDownloadRequest, od::kCaptureContent, 0, 4);
  EXPECT_FALSE(c.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, kSdoAbortValueRange);

  CameraNode blind;
  blind.image_sensor = false;
  for (const uint32_t v : {0u, 1u, 3u}) {
    m = request(SdoKind::kDownloadRequest, od::kCaptureContent, 0, v);
    EXPECT_FALSE(blind.sdo(&m, &io, &start)) << v;
    EXPECT_EQ(m.value, kSdoAbortValueRange);
  }
  m = request(SdoKind::kDownloadRequest, od::kCaptureContent, 0, od::kCaptureGroundTruth);
  EXPECT_TRUE(blind.sdo(&m, &io, &start));
  m = request(SdoKind::kUploadRequest, od::kCaptureContent, 0);
  ASSERT_TRUE(blind.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, od::kCaptureGroundTruth);
  EXPECT_EQ(m.size, 1);
}

TEST(CameraNode, PhysicsIsReadOnlyAndHeartbeatIsServed) {
  RecordingIo io;
  Start start = Start::kNone;
  CameraNode c;
  c.physics = od::kPhysicsOde;
  SdoMessage m = request(SdoKind::kUploadRequest, od::kSimulatorPhysics, 0);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, od::kPhysicsOde);
  m = request(SdoKind::kDownloadRequest, od::kSimulatorPhysics, 0, 0);
  EXPECT_FALSE(c.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, kSdoAbortReadOnly);
  m = request(SdoKind::kDownloadRequest, od::kHeartbeatProducerTime, 0, 30);
  ASSERT_TRUE(c.sdo(&m, &io, &start));
  EXPECT_EQ(c.heartbeat_ms, 30);
  m = request(SdoKind::kUploadRequest, 0x6041, 0);
  EXPECT_FALSE(c.sdo(&m, &io, &start));
  EXPECT_EQ(m.value, kSdoAbortNoObject);
}

TEST(CameraNode, CaptureRequestsAndResets) {
  RecordingIo io;
  CameraNode c;
  c.id = kCameraNode;
  c.set_nmt(NmtState::kPreOperational, &io);
  EXPECT_EQ(c.on_capture({0}), CameraNode::Capture::kIgnore) << "pre-operational";
  c.set_nmt(NmtState::kOperational, &io);
  EXPECT_EQ(c.on_capture({0}), CameraNode::Capture::kStale) << "no episode started";
  c.episode_started = true;
  c.episode = 4;
  EXPECT_EQ(c.on_capture({3}), CameraNode::Capture::kStale);
  EXPECT_EQ(c.on_capture({4}), CameraNode::Capture::kTake);

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
