// A joint node (firmware/protocol/joint_node.hpp): RPDO1 in operational only, the position
// limit (clamped; EMCY 0x8612 once per excursion), following the target at SYNC, TPDO1, and
// the joint's object dictionary.
#include <gtest/gtest.h>

#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/joint_node.hpp"
#include "tests/protocol/node_test_io.hpp"

using namespace curio::protocol;
using curio::protocol::test::RecordingIo;
using curio::protocol::test::sdo_request;
using Event = NodeIo::Event;

namespace {

constexpr int32_t kLimit = 3141593;

JointNode operational_joint(RecordingIo* io) {
  JointNode j;
  j.id = 3;
  j.limit_counts = kLimit;
  j.set_nmt(NmtState::kPreOperational, io);
  j.set_nmt(NmtState::kOperational, io);
  io->clear();
  return j;
}

void enable(JointNode* j, RecordingIo* io) {
  j->drive.mode = cia402::kModeCyclicSynchronousPosition;
  for (const uint16_t cw : {cia402::kCwShutdown, cia402::kCwSwitchOn, cia402::kCwEnableOperation})
    j->on_command({j->id, cw, 0}, io);
}

}  // namespace

TEST(JointNode, CommandsOnlyInOperational) {
  RecordingIo io;
  JointNode j = operational_joint(&io);
  j.set_nmt(NmtState::kPreOperational, &io);
  j.on_command({3, cia402::kCwShutdown, 1000}, &io);
  EXPECT_EQ(j.drive.state, cia402::DriveState::kSwitchOnDisabled);
  EXPECT_EQ(j.drive.target_counts, 0);
  j.set_nmt(NmtState::kOperational, &io);
  j.on_command({3, cia402::kCwShutdown, 1000}, &io);
  EXPECT_EQ(j.drive.state, cia402::DriveState::kReadyToSwitchOn);
  EXPECT_EQ(j.drive.target_counts, 1000);
  EXPECT_TRUE(io.frames.empty());
}

TEST(JointNode, FollowsTheTargetOnlyWhenOperationalAndEnabled) {
  RecordingIo io;
  JointNode j = operational_joint(&io);
  j.on_command({3, 0, 500'000}, &io);
  EXPECT_FALSE(j.follows_target());
  EXPECT_EQ(j.angle_at_sync_rad(0.25), 0.25) << "not enabled: holds";
  enable(&j, &io);
  j.on_command({3, cia402::kCwEnableOperation, -500'000}, &io);
  EXPECT_TRUE(j.follows_target());
  EXPECT_EQ(j.angle_at_sync_rad(0.25), -0.5);
  j.set_nmt(NmtState::kStopped, &io);
  EXPECT_FALSE(j.follows_target()) << "stopped: holds";
  EXPECT_EQ(j.angle_at_sync_rad(0.25), 0.25);
}

TEST(JointNode, TargetBeyondTheLimitIsClampedAndReportedOnce) {
  RecordingIo io;
  JointNode j = operational_joint(&io);
  enable(&j, &io);
  j.on_command({3, cia402::kCwEnableOperation, kLimit}, &io);
  j.on_command({3, cia402::kCwEnableOperation, -kLimit}, &io);
  EXPECT_EQ(j.drive.target_counts, -kLimit) << "the limit itself is inside";
  EXPECT_TRUE(io.frames.empty());

  j.on_command({3, cia402::kCwEnableOperation, kLimit + 1}, &io);
  EXPECT_EQ(j.drive.state, cia402::DriveState::kOperationEnabled) << "clamped, no fault";
  EXPECT_EQ(j.drive.target_counts, kLimit);
  ASSERT_EQ(io.frames.size(), 1u);
  Emergency e;
  ASSERT_EQ(decode_emcy(io.frames[0], &e), CodecStatus::kOk);
  EXPECT_EQ(e.node, 3);
  EXPECT_EQ(e.error_code, od::kEmcyPositionLimit);
  EXPECT_EQ(e.error_register, 0x00) << "no fault";
  EXPECT_EQ(io.count_of(Event::kEmcySent), 1u);

  j.on_command({3, cia402::kCwEnableOperation, kLimit + 1000}, &io);
  EXPECT_EQ(io.frames.size(), 1u) << "the same excursion: no second EMCY";
  EXPECT_EQ(io.count_of(Event::kTargetRejected), 2u) << "but every clamp is counted";
  EXPECT_TRUE(j.follows_target());
  j.on_command({3, cia402::kCwEnableOperation, 0}, &io);
  j.on_command({3, cia402::kCwEnableOperation, -kLimit - 1}, &io);
  EXPECT_EQ(j.drive.target_counts, -kLimit);
  EXPECT_EQ(io.frames.size(), 2u) << "a new excursion is reported again";

  // 0x607D narrower than the joint range clamps there.
  SdoMessage m = sdo_request(SdoKind::kDownloadRequest, 3, od::kSoftwarePositionLimit,
                             od::kPositionLimitMaxSub, 1'000'000);
  ASSERT_TRUE(j.sdo(&m, 0, &io));
  j.on_command({3, cia402::kCwEnableOperation, 1'500'000}, &io);
  EXPECT_EQ(j.drive.target_counts, 1'000'000);
}

TEST(JointNode, FaultSendsEmcyWithTheErrorCode) {
  RecordingIo io;
  JointNode j = operational_joint(&io);
  j.fault(od::kEmcyFollowingError, &io);
  ASSERT_EQ(io.frames.size(), 1u);
  Emergency e;
  ASSERT_EQ(decode_emcy(io.frames[0], &e), CodecStatus::kOk);
  EXPECT_EQ(e.error_code, od::kEmcyFollowingError);
  j.fault(od::kEmcyFollowingError, &io);
  EXPECT_EQ(io.frames.size(), 1u);
}

TEST(JointNode, FeedbackIsStatuswordAndActualPosition) {
  RecordingIo io;
  JointNode j = operational_joint(&io);
  enable(&j, &io);
  JointFeedback fb;
  ASSERT_EQ(decode_joint_feedback(j.feedback(-1234), &fb), CodecStatus::kOk);
  EXPECT_EQ(fb.node, 3);
  EXPECT_EQ(fb.statusword, 0x1627);
  EXPECT_EQ(fb.actual_counts, -1234);
}

TEST(JointNode, ObjectDictionary) {
  RecordingIo io;
  JointNode j = operational_joint(&io);
  auto read = [&](uint16_t index, uint8_t sub, uint32_t* value, uint8_t* size = nullptr) {
    SdoMessage m = sdo_request(SdoKind::kUploadRequest, 3, index, sub);
    const bool ok = j.sdo(&m, -42, &io);
    *value = m.value;
    if (size != nullptr) *size = m.size;
    return ok;
  };
  auto write = [&](uint16_t index, uint8_t sub, uint32_t value, uint32_t* abort) {
    SdoMessage m = sdo_request(SdoKind::kDownloadRequest, 3, index, sub, value);
    const bool ok = j.sdo(&m, -42, &io);
    *abort = ok ? 0 : m.value;
    return ok;
  };
  uint32_t v = 0, abort = 0;
  uint8_t size = 0;

  ASSERT_TRUE(write(cia402::kControlword, 0, cia402::kCwShutdown, &abort));
  EXPECT_EQ(j.drive.state, cia402::DriveState::kReadyToSwitchOn);
  ASSERT_TRUE(read(cia402::kControlword, 0, &v, &size));
  EXPECT_EQ(v, cia402::kCwShutdown);
  EXPECT_EQ(size, 2);
  ASSERT_TRUE(read(cia402::kStatusword, 0, &v, &size));
  EXPECT_EQ(v, 0x0221u);
  EXPECT_FALSE(write(cia402::kStatusword, 0, 0, &abort));
  EXPECT_EQ(abort, kSdoAbortReadOnly);

  EXPECT_FALSE(write(cia402::kModesOfOperation, 0, 1, &abort));
  EXPECT_EQ(abort, kSdoAbortValueRange) << "only cyclic synchronous position";
  ASSERT_TRUE(write(cia402::kModesOfOperation, 0, 8, &abort));
  ASSERT_TRUE(read(cia402::kModesOfOperation, 0, &v, &size));
  EXPECT_EQ(v, 8u);
  EXPECT_EQ(size, 1);
  ASSERT_TRUE(read(cia402::kModesOfOperationDisplay, 0, &v));
  EXPECT_EQ(v, 8u);
  EXPECT_FALSE(write(cia402::kModesOfOperationDisplay, 0, 8, &abort));
  EXPECT_EQ(abort, kSdoAbortReadOnly);

  ASSERT_TRUE(read(cia402::kPositionActualValue, 0, &v, &size));
  EXPECT_EQ(static_cast<int32_t>(v), -42);
  EXPECT_EQ(size, 4);
  EXPECT_FALSE(write(cia402::kPositionActualValue, 0, 0, &abort));
  EXPECT_EQ(abort, kSdoAbortReadOnly);

  ASSERT_TRUE(write(cia402::kTargetPosition, 0, static_cast<uint32_t>(-kLimit), &abort));
  ASSERT_TRUE(read(cia402::kTargetPosition, 0, &v));
  EXPECT_EQ(static_cast<int32_t>(v), -kLimit);
  ASSERT_TRUE(write(cia402::kTargetPosition, 0, kLimit + 1, &abort));
  EXPECT_EQ(j.drive.target_counts, kLimit) << "clamped to the limit";
  EXPECT_EQ(j.drive.state, cia402::DriveState::kReadyToSwitchOn) << "no fault";
  EXPECT_EQ(io.count_of(Event::kTargetRejected), 1u);
  EXPECT_EQ(io.count_of(Event::kEmcySent), 1u) << "EMCY 0x8612, reported";
  io.clear();

  ASSERT_TRUE(read(cia402::kInterpolationTimePeriod, od::kInterpolationPeriodValueSub, &v));
  EXPECT_EQ(v, 10u);
  ASSERT_TRUE(read(cia402::kInterpolationTimePeriod, od::kInterpolationPeriodIndexSub, &v));
  EXPECT_EQ(v, 0xFDu);  // −3
  ASSERT_TRUE(write(cia402::kInterpolationTimePeriod, od::kInterpolationPeriodValueSub, 5, &abort));
  ASSERT_TRUE(
      write(cia402::kInterpolationTimePeriod, od::kInterpolationPeriodIndexSub, 0xFE, &abort));
  EXPECT_EQ(j.drive.ip_value, 5);
  EXPECT_EQ(j.drive.ip_index, -2);
  EXPECT_FALSE(read(cia402::kInterpolationTimePeriod, 3, &v));
  EXPECT_EQ(v, kSdoAbortNoSubindex);
  ASSERT_TRUE(read(cia402::kInterpolationTimePeriod, 0, &v));
  EXPECT_EQ(v, 2u);
  EXPECT_FALSE(
      write(cia402::kInterpolationTimePeriod, od::kInterpolationPeriodIndexSub, 1, &abort));
  EXPECT_EQ(abort, kSdoAbortValueRange) << "10 s periods are not a drive's";

  ASSERT_TRUE(write(od::kHeartbeatProducerTime, 0, 20, &abort));
  EXPECT_EQ(j.heartbeat_ms, 20);
  EXPECT_FALSE(read(cia402::kControlword, 1, &v));
  EXPECT_EQ(v, kSdoAbortNoSubindex);
  EXPECT_FALSE(read(0x6098, 0, &v));
  EXPECT_EQ(v, kSdoAbortNoObject);
  EXPECT_TRUE(io.frames.empty());
}

TEST(JointNode, ResetApplicationRestoresTheDrive) {
  RecordingIo io;
  JointNode j = operational_joint(&io);
  enable(&j, &io);
  j.on_command({3, cia402::kCwEnableOperation, 77}, &io);
  j.drive.ip_value = 1;
  j.reset_application();
  EXPECT_EQ(j.drive.state, cia402::DriveState::kSwitchOnDisabled);
  EXPECT_EQ(j.drive.controlword, 0);
  EXPECT_EQ(j.drive.mode, 0);
  EXPECT_EQ(j.drive.target_counts, 0);
  EXPECT_EQ(j.drive.ip_value, 10);
  EXPECT_EQ(j.id, 3);
  EXPECT_EQ(j.limit_counts, kLimit);
}
