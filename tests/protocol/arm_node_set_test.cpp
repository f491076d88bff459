// The arm's eight nodes together (firmware/protocol/arm_node_set.hpp): power-on boot-ups,
// addressing by node id, NMT to one node and to all, RPDO1 routing, TPDO1 of the operational
// joints, heartbeats, and the SDO server's dispatch.
#include <gtest/gtest.h>

#include "firmware/protocol/arm_node_set.hpp"
#include "tests/protocol/node_test_io.hpp"

using namespace curio::protocol;
using curio::protocol::test::RecordingIo;
using curio::protocol::test::sdo_request;
using Start = CameraNode::EpisodeStart;

constexpr int32_t kLimit = 1000;  // the joints' limit, counts

TEST(ArmNodeSet, PowerOnBootsAllEightNodes) {
  RecordingIo io;
  ArmNodeSet nodes;
  nodes.power_on(kLimit, &io);
  ASSERT_EQ(io.frames.size(), 8u);
  for (int j = 0; j < kJointNodes; ++j) {
    EXPECT_EQ(io.frames[j].id, 0x700u + kFirstJointNode + j);
    EXPECT_EQ(nodes.joints[j].limit_counts, kLimit);
    EXPECT_EQ(nodes.joints[j].nmt, NmtState::kPreOperational);
  }
  EXPECT_EQ(io.frames[7].id, 0x700u + kCameraNode);
  EXPECT_EQ(nodes.node(1), &nodes.joints[0]);
  EXPECT_EQ(nodes.node(7), &nodes.joints[6]);
  EXPECT_EQ(nodes.node(kCameraNode), &nodes.camera);
  EXPECT_EQ(nodes.node(0), nullptr);
  EXPECT_EQ(nodes.node(8), nullptr);
  EXPECT_EQ(nodes.next_heartbeat_due_us(), UINT64_MAX);
}

TEST(ArmNodeSet, NmtToOneNodeAndToAll) {
  RecordingIo io;
  ArmNodeSet nodes;
  nodes.power_on(kLimit, &io);
  EXPECT_EQ(nodes.on_nmt({NmtCommand::kStart, 0}, &io), NmtReset::kNone);
  for (const JointNode& j : nodes.joints) EXPECT_EQ(j.nmt, NmtState::kOperational);
  EXPECT_EQ(nodes.camera.nmt, NmtState::kOperational);

  nodes.joints[2].drive.state = cia402::DriveState::kOperationEnabled;
  nodes.joints[3].drive.state = cia402::DriveState::kOperationEnabled;
  nodes.camera.episode_started = true;
  EXPECT_EQ(nodes.on_nmt({NmtCommand::kResetNode, 3}, &io), NmtReset::kNone);
  EXPECT_EQ(nodes.joints[2].drive.state, cia402::DriveState::kSwitchOnDisabled);
  EXPECT_EQ(nodes.joints[2].nmt, NmtState::kPreOperational);
  EXPECT_EQ(nodes.joints[3].drive.state, cia402::DriveState::kOperationEnabled);
  EXPECT_EQ(nodes.on_nmt({NmtCommand::kResetCommunication, 4}, &io), NmtReset::kNone);
  EXPECT_EQ(nodes.joints[3].drive.state, cia402::DriveState::kOperationEnabled)
      << "a communication reset keeps the drive";
  EXPECT_TRUE(nodes.camera.episode_started);

  EXPECT_EQ(nodes.on_nmt({NmtCommand::kResetCommunication, kCameraNode}, &io),
            NmtReset::kCommunication);
  EXPECT_FALSE(nodes.camera.episode_started);
  EXPECT_EQ(nodes.on_nmt({NmtCommand::kResetNode, 0}, &io), NmtReset::kApplication);
  EXPECT_EQ(nodes.joints[3].drive.state, cia402::DriveState::kSwitchOnDisabled);
}

TEST(ArmNodeSet, CommandsFeedbackAndHeartbeats) {
  RecordingIo io;
  ArmNodeSet nodes;
  nodes.power_on(kLimit, &io);
  nodes.on_nmt({NmtCommand::kStart, 2}, &io);
  nodes.on_nmt({NmtCommand::kStart, 5}, &io);
  nodes.on_command({2, cia402::kCwShutdown, 400}, &io);
  EXPECT_EQ(nodes.joints[1].drive.target_counts, 400);
  EXPECT_EQ(nodes.joints[1].drive.state, cia402::DriveState::kReadyToSwitchOn);
  nodes.on_command({3, cia402::kCwShutdown, 400}, &io);
  EXPECT_EQ(nodes.joints[2].drive.target_counts, 0) << "joint 3 is pre-operational";

  io.clear();
  const int32_t counts[kJointNodes] = {10, 20, 30, 40, 50, 60, 70};
  nodes.send_feedback(counts, &io);
  ASSERT_EQ(io.frames.size(), 2u) << "the operational joints only";
  JointFeedback fb;
  ASSERT_EQ(decode_joint_feedback(io.frames[0], &fb), CodecStatus::kOk);
  EXPECT_EQ(fb.node, 2);
  EXPECT_EQ(fb.actual_counts, 20);
  ASSERT_EQ(decode_joint_feedback(io.frames[1], &fb), CodecStatus::kOk);
  EXPECT_EQ(fb.node, 5);
  EXPECT_EQ(fb.actual_counts, 50);

  nodes.joints[4].heartbeat_ms = 10;
  nodes.joints[4].next_heartbeat_us = 5000;
  nodes.camera.heartbeat_ms = 10;
  nodes.camera.next_heartbeat_us = 7000;
  EXPECT_EQ(nodes.next_heartbeat_due_us(), 5000u);
  io.clear();
  nodes.heartbeats_due(6000, &io);
  ASSERT_EQ(io.frames.size(), 1u);
  EXPECT_EQ(io.frames[0].id, 0x705u);
}

TEST(ArmNodeSet, SdoGoesToTheAddressedNode) {
  RecordingIo io;
  ArmNodeSet nodes;
  nodes.power_on(kLimit, &io);
  const int32_t counts[kJointNodes] = {-1, -2, -3, -4, -5, -6, -7};
  Start start = Start::kReplay;
  SdoMessage answer;
  auto ask = [&](SdoKind kind, uint8_t node, uint16_t index, uint8_t sub, uint32_t value = 0) {
    return nodes.on_sdo(sdo_request(kind, node, index, sub, value), counts, &io, &start, &answer);
  };
  ASSERT_TRUE(ask(SdoKind::kUploadRequest, 6, cia402::kPositionActualValue, 0));
  EXPECT_EQ(answer.kind, SdoKind::kUploadResponse);
  EXPECT_EQ(answer.node, 6);
  EXPECT_EQ(static_cast<int32_t>(answer.value), -6);
  EXPECT_EQ(start, Start::kNone);
  ASSERT_TRUE(
      ask(SdoKind::kDownloadRequest, kCameraNode, od::kEpisodeControl, od::kEpisodeStartSub, 9));
  EXPECT_EQ(answer.kind, SdoKind::kDownloadResponse);
  EXPECT_EQ(start, Start::kNew);
  EXPECT_EQ(nodes.camera.episode, 9u);
  ASSERT_TRUE(ask(SdoKind::kUploadRequest, kCameraNode, cia402::kPositionActualValue, 0));
  EXPECT_EQ(answer.kind, SdoKind::kNodeAbort) << "a joint object on the camera";
  EXPECT_EQ(answer.value, kSdoAbortNoObject);
  EXPECT_EQ(io.count_of(NodeIo::Event::kSdoRequest), 3u);
  EXPECT_EQ(io.count_of(NodeIo::Event::kSdoAbort), 1u);

  EXPECT_FALSE(ask(SdoKind::kClientAbort, 6, cia402::kStatusword, 0)) << "no answer";
  EXPECT_EQ(io.count_of(NodeIo::Event::kSdoIgnored), 0u);
  EXPECT_FALSE(ask(SdoKind::kUploadRequest, 9, cia402::kStatusword, 0)) << "no such node";
  nodes.on_nmt({NmtCommand::kStop, 6}, &io);
  EXPECT_FALSE(ask(SdoKind::kUploadRequest, 6, cia402::kStatusword, 0)) << "stopped";
  EXPECT_EQ(io.count_of(NodeIo::Event::kSdoIgnored), 2u);
  EXPECT_EQ(io.count_of(NodeIo::Event::kSdoRequest), 3u);
}
