// The CANopen node side (firmware/protocol/canopen_node.hpp): boot-up and heartbeats on NMT
// changes, the heartbeat producer's schedule, NMT resets, object 0x1017 and the SDO answer.
#include <gtest/gtest.h>

#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/canopen_node.hpp"
#include "tests/protocol/node_test_io.hpp"

using namespace curio::protocol;
using curio::protocol::test::RecordingIo;
using curio::protocol::test::sdo_request;

namespace {

Heartbeat heartbeat_of(const CanFrame& f) {
  Heartbeat h;
  EXPECT_EQ(decode_heartbeat(f, &h), CodecStatus::kOk);
  return h;
}

CanopenNode booted(RecordingIo* io, uint8_t id = 5) {
  CanopenNode n;
  n.id = id;
  n.set_nmt(NmtState::kPreOperational, io);
  io->clear();
  return n;
}

}  // namespace

TEST(CanopenNode, BootUpOnceThenSilentWithoutHeartbeat) {
  RecordingIo io;
  CanopenNode n;
  n.id = 5;
  n.set_nmt(NmtState::kPreOperational, &io);
  ASSERT_EQ(io.frames.size(), 1u);
  EXPECT_EQ(io.frames[0].id, 0x705u);
  EXPECT_EQ(heartbeat_of(io.frames[0]).state, NmtState::kBootUp);
  EXPECT_EQ(io.count_of(NodeIo::Event::kHeartbeatSent), 1u);
  n.set_nmt(NmtState::kOperational, &io);
  n.heartbeat_due(1'000'000, &io);
  EXPECT_EQ(io.frames.size(), 1u) << "heartbeat producer time 0: no heartbeats";
  EXPECT_EQ(n.next_heartbeat_due_us(), UINT64_MAX);
}

TEST(CanopenNode, HeartbeatAtOnceOnChangeAndEveryPeriod) {
  RecordingIo io;
  CanopenNode n = booted(&io);
  io.now = 1000;
  SdoMessage m = sdo_request(SdoKind::kDownloadRequest, 5, od::kHeartbeatProducerTime, 0, 100);
  ASSERT_TRUE(n.sdo_heartbeat_time(&m, &io));
  EXPECT_EQ(n.heartbeat_ms, 100);
  EXPECT_EQ(n.next_heartbeat_due_us(), 101'000u);
  EXPECT_TRUE(io.frames.empty());

  n.heartbeat_due(100'999, &io);
  EXPECT_TRUE(io.frames.empty());
  io.now = 101'500;  // the schedule counts from the time of sending
  n.heartbeat_due(101'000, &io);
  ASSERT_EQ(io.frames.size(), 1u);
  EXPECT_EQ(heartbeat_of(io.frames[0]).state, NmtState::kPreOperational);
  EXPECT_EQ(n.next_heartbeat_due_us(), 201'500u);

  io.now = 150'000;
  n.set_nmt(NmtState::kOperational, &io);
  ASSERT_EQ(io.frames.size(), 2u);
  EXPECT_EQ(heartbeat_of(io.frames[1]).state, NmtState::kOperational);
  EXPECT_EQ(n.next_heartbeat_due_us(), 250'000u);
  n.set_nmt(NmtState::kOperational, &io);
  EXPECT_EQ(io.frames.size(), 2u) << "no change, no extra heartbeat";
  EXPECT_EQ(io.count_of(NodeIo::Event::kHeartbeatSent), 2u);
}

TEST(CanopenNode, NmtCommandsAndResets) {
  RecordingIo io;
  CanopenNode n = booted(&io);
  EXPECT_TRUE(n.serves_sdo());
  EXPECT_EQ(n.on_nmt(NmtCommand::kStart, &io), NmtReset::kNone);
  EXPECT_EQ(n.nmt, NmtState::kOperational);
  EXPECT_EQ(n.on_nmt(NmtCommand::kStop, &io), NmtReset::kNone);
  EXPECT_EQ(n.nmt, NmtState::kStopped);
  EXPECT_FALSE(n.serves_sdo());
  EXPECT_EQ(n.on_nmt(NmtCommand::kEnterPreOperational, &io), NmtReset::kNone);
  EXPECT_EQ(n.nmt, NmtState::kPreOperational);
  EXPECT_TRUE(io.frames.empty()) << "heartbeats off: state changes are silent";

  n.heartbeat_ms = 50;
  EXPECT_EQ(n.on_nmt(NmtCommand::kResetCommunication, &io), NmtReset::kCommunication);
  EXPECT_EQ(n.heartbeat_ms, 0) << "a reset loses the configuration";
  EXPECT_EQ(n.nmt, NmtState::kPreOperational);
  ASSERT_EQ(io.frames.size(), 1u);
  EXPECT_EQ(heartbeat_of(io.frames[0]).state, NmtState::kBootUp);
  EXPECT_EQ(n.on_nmt(NmtCommand::kResetNode, &io), NmtReset::kApplication);
  ASSERT_EQ(io.frames.size(), 2u);
  EXPECT_EQ(heartbeat_of(io.frames[1]).state, NmtState::kBootUp);
  CanopenNode booting;
  EXPECT_FALSE(booting.serves_sdo());
}

TEST(CanopenNode, HeartbeatObjectReadAndBadSubindex) {
  RecordingIo io;
  CanopenNode n = booted(&io);
  n.heartbeat_ms = 250;
  SdoMessage m = sdo_request(SdoKind::kUploadRequest, 5, od::kHeartbeatProducerTime, 0);
  ASSERT_TRUE(n.sdo_heartbeat_time(&m, &io));
  EXPECT_EQ(m.value, 250u);
  EXPECT_EQ(m.size, 2);
  m = sdo_request(SdoKind::kDownloadRequest, 5, od::kHeartbeatProducerTime, 1, 7);
  EXPECT_FALSE(n.sdo_heartbeat_time(&m, &io));
  EXPECT_EQ(m.value, kSdoAbortNoSubindex) << "0x1017 exists, its sub-index 1 does not";
  EXPECT_EQ(n.heartbeat_ms, 250);
}

TEST(CanopenNode, SdoAnswerOfEachKind) {
  const SdoMessage up = sdo_request(SdoKind::kUploadRequest, 5, 0x6041, 0);
  SdoMessage handled = up;
  sdo_value(&handled, 0x1627, 2);
  SdoMessage a = sdo_answer(up, handled, true);
  EXPECT_EQ(a.kind, SdoKind::kUploadResponse);
  EXPECT_EQ(a.node, 5);
  EXPECT_EQ(a.index, 0x6041);
  EXPECT_EQ(a.value, 0x1627u);
  EXPECT_EQ(a.size, 2);

  const SdoMessage down = sdo_request(SdoKind::kDownloadRequest, 5, 0x6040, 0, 0x0F);
  a = sdo_answer(down, down, true);
  EXPECT_EQ(a.kind, SdoKind::kDownloadResponse);
  EXPECT_EQ(a.value, 0u);

  handled = down;
  EXPECT_FALSE(sdo_abort(&handled, kSdoAbortReadOnly));
  a = sdo_answer(down, handled, false);
  EXPECT_EQ(a.kind, SdoKind::kNodeAbort);
  EXPECT_EQ(a.index, 0x6040);
  EXPECT_EQ(a.value, kSdoAbortReadOnly);
  CanFrame f = encode_sdo(a);
  EXPECT_EQ(f.id, 0x585u);
}
