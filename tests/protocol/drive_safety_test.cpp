// The simulated drives' safety side (firmware/protocol): the heartbeat consumer (0x1016) and
// the joints' reaction to a lost controller (EMCY 0x8130, 0x6007), the quick stop and fault
// reaction ramps on 0x6085, the software position limits (0x607D), the speed limit
// (0x607F/0x6080), the following error (0x6065/0x6066, EMCY 0x8611), the CiA 301 identity
// (0x1000, 0x1001, 0x1018, 0x6502) and the abort codes a standard master expects.
#include <gtest/gtest.h>

#include "firmware/protocol/arm_node_set.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/cia402_motion.hpp"
#include "firmware/protocol/heartbeat_consumer.hpp"
#include "firmware/protocol/joint_node.hpp"
#include "tests/protocol/node_test_io.hpp"

using namespace curio::protocol;
using curio::protocol::test::RecordingIo;
using curio::protocol::test::sdo_request;
using Event = NodeIo::Event;
using cia402::DriveState;

namespace {

constexpr int32_t kRange = 3141593;
constexpr uint32_t kPeriodUs = 10'000;

JointNode enabled_joint(RecordingIo* io) {
  JointNode j;
  j.id = 2;
  j.limit_counts = kRange;
  j.identity = JointNode::joint_identity(2);
  j.set_nmt(NmtState::kPreOperational, io);
  j.set_nmt(NmtState::kOperational, io);
  j.drive.mode = cia402::kModeCyclicSynchronousPosition;
  for (const uint16_t cw : {cia402::kCwShutdown, cia402::kCwSwitchOn, cia402::kCwEnableOperation})
    j.on_command({j.id, cw, 0}, io);
  io->clear();
  return j;
}

// SDO on the joint: true, or false with the abort code in *value.
bool write(JointNode* j, uint16_t index, uint8_t sub, uint32_t value, uint32_t* abort,
           RecordingIo* io) {
  SdoMessage m = sdo_request(SdoKind::kDownloadRequest, j->id, index, sub, value);
  const bool ok = j->sdo(&m, 0, io);
  *abort = ok ? 0 : m.value;
  return ok;
}
bool read(JointNode* j, uint16_t index, uint8_t sub, uint32_t* value, RecordingIo* io) {
  SdoMessage m = sdo_request(SdoKind::kUploadRequest, j->id, index, sub);
  const bool ok = j->sdo(&m, 0, io);
  *value = m.value;
  return ok;
}

// `steps` SYNC periods toward `target` (the world follows the demand exactly).
void follow(JointNode* j, int32_t target, int steps, RecordingIo* io) {
  for (int i = 0; i < steps; ++i) {
    j->on_command({j->id, cia402::kCwEnableOperation, target}, io);
    const double rad = j->angle_at_sync_rad(counts_to_angle(j->drive.motion.demand_counts), io);
    int32_t actual = 0;
    ASSERT_EQ(angle_to_counts(rad, &actual), CodecStatus::kOk);
    j->after_step(actual, io);
  }
}

}  // namespace

TEST(HeartbeatConsumer, ArmedByTheFirstHeartbeatReportsOneMissAndRearms) {
  HeartbeatConsumer c;
  EXPECT_FALSE(c.active());
  EXPECT_FALSE(c.configure(0x01000000)) << "reserved bits";
  EXPECT_FALSE(c.configure(od::consumer_heartbeat_entry(0x80, 100))) << "node 128";
  ASSERT_TRUE(c.configure(od::consumer_heartbeat_entry(127, 200)));
  EXPECT_EQ(c.entry(), 0x007F00C8u);
  EXPECT_FALSE(c.check(10'000'000)) << "not armed before the producer's first heartbeat";
  EXPECT_EQ(c.deadline_us(), UINT64_MAX);
  EXPECT_FALSE(c.on_heartbeat(5, 1'000'000)) << "another node";
  EXPECT_FALSE(c.armed());
  ASSERT_TRUE(c.on_heartbeat(127, 1'000'000));
  EXPECT_EQ(c.deadline_us(), 1'200'000u);
  EXPECT_FALSE(c.check(1'200'000)) << "exactly the consumer time is not a miss";
  EXPECT_TRUE(c.check(1'200'001));
  EXPECT_TRUE(c.missed());
  EXPECT_FALSE(c.check(5'000'000)) << "once per silence";
  ASSERT_TRUE(c.on_heartbeat(127, 6'000'000));
  EXPECT_FALSE(c.missed());
  EXPECT_FALSE(c.check(6'150'000));
  EXPECT_TRUE(c.check(6'250'000));
  c.reset();
  EXPECT_EQ(c.entry(), 0u);
  ASSERT_TRUE(c.configure(od::consumer_heartbeat_entry(127, 0)));
  EXPECT_FALSE(c.on_heartbeat(127, 0)) << "time 0: not used";
}

TEST(Cia402Motion, TargetStepsAreLimitedToTheMaximumVelocity) {
  cia402::MotionLimits l;
  l.max_velocity = 1'000'000;  // 10,000 counts per 10 ms
  cia402::Motion m;
  EXPECT_TRUE(m.follow(25'000, l, kPeriodUs));
  EXPECT_EQ(m.demand_counts, 10'000);
  EXPECT_EQ(m.velocity_counts_s, 1'000'000);
  EXPECT_TRUE(m.follow(25'000, l, kPeriodUs));
  EXPECT_FALSE(m.follow(25'000, l, kPeriodUs));
  EXPECT_EQ(m.demand_counts, 25'000);
  EXPECT_EQ(m.velocity_counts_s, 500'000);
  EXPECT_FALSE(m.follow(15'000, l, kPeriodUs)) << "exactly the limit is not limited";
  EXPECT_EQ(m.velocity_counts_s, -1'000'000);
  EXPECT_EQ(cia402::max_step_counts(od::kConfigMaxVelocityCounts, kPeriodUs), kRange)
      << "Curio's configured limit: π rad per 10 ms period";
}

TEST(Cia402Motion, QuickStopRampDeceleratesToStandstillOnTheDeceleration) {
  cia402::MotionLimits l;
  l.deceleration = 10'000'000;  // 10 rad/s²: 1 rad/s lost per 100 ms
  cia402::Motion m;
  m.velocity_counts_s = 1'000'000;  // 1 rad/s
  int periods = 0;
  while (!m.ramp(l, kPeriodUs)) ++periods;
  ++periods;
  EXPECT_EQ(periods, 10) << "v / a = 100 ms";
  EXPECT_EQ(m.demand_counts, 50'000) << "v² / 2a = 0.05 rad";
  // Within one period: the rest of the ramp, v²/2a.
  m = cia402::Motion{};
  m.velocity_counts_s = -1'000'000;
  l.deceleration = 1'000'000'000;
  EXPECT_TRUE(m.ramp(l, kPeriodUs));
  EXPECT_EQ(m.demand_counts, -500);
  // A software limit on the way stops the joint there.
  m = cia402::Motion{};
  m.velocity_counts_s = 1'000'000;
  l.deceleration = 10'000'000;
  l.max_counts = 20'000;
  int n = 0;
  while (!m.ramp(l, kPeriodUs)) ++n;
  EXPECT_EQ(m.demand_counts, 20'000);
  EXPECT_LT(n, 9);
}

TEST(Cia402Motion, FollowingErrorTripsOnceAfterTheTimeOut) {
  cia402::FollowingErrorMonitor f;
  EXPECT_FALSE(f.check(5000, 0, od::kFollowingErrorOff, 0, 0)) << "0xFFFFFFFF: off";
  EXPECT_FALSE(f.check(1000, 0, 1000, 20, 0)) << "on the window's edge: inside";
  EXPECT_FALSE(f.check(1001, 0, 1000, 20, 10'000));
  EXPECT_FALSE(f.check(1001, 0, 1000, 20, 20'000));
  EXPECT_TRUE(f.check(-2000, 0, 1000, 20, 30'000)) << "outside for 20 ms";
  EXPECT_FALSE(f.check(-2000, 0, 1000, 20, 40'000)) << "once";
  EXPECT_FALSE(f.check(0, 0, 1000, 20, 50'000));
  EXPECT_FALSE(f.check(5000, 0, 1000, 20, 60'000));
  EXPECT_TRUE(f.check(5000, 0, 1000, 20, 80'000)) << "a new excursion trips again";
}

TEST(JointSafety, MissedControllerHeartbeatSendsEmcyAndQuickStopsToSwitchOnDisabled) {
  RecordingIo io;
  JointNode j = enabled_joint(&io);
  uint32_t abort = 0;
  ASSERT_TRUE(write(&j, od::kConsumerHeartbeatTime, 1,
                    od::consumer_heartbeat_entry(od::kDefaultMasterNode, 200), &abort, &io));
  ASSERT_TRUE(write(&j, od::kAbortConnectionOption, 0, 3, &abort, &io));
  ASSERT_TRUE(write(&j, od::kQuickStopDeceleration, 0, 100'000'000, &abort, &io));  // 100 rad/s²
  io.now = 1'000'000;
  j.on_heartbeat({od::kDefaultMasterNode, NmtState::kOperational}, &io);
  io.now = 1'195'000;
  follow(&j, 10'000, 1, &io);  // moving at 1 rad/s: targets still come, the heartbeat does not
  EXPECT_EQ(j.drive.motion.velocity_counts_s, 1'000'000);
  EXPECT_FALSE(j.consumer_due(1'200'000, &io));
  ASSERT_TRUE(io.frames.empty());
  EXPECT_TRUE(j.consumer_due(1'200'001, &io));
  ASSERT_EQ(io.frames.size(), 1u);
  Emergency e;
  ASSERT_EQ(decode_emcy(io.frames[0], &e), CodecStatus::kOk);
  EXPECT_EQ(e.node, 2);
  EXPECT_EQ(e.error_code, od::kEmcyHeartbeatLost);
  EXPECT_EQ(e.error_register, od::kErrorRegisterCommunication);
  EXPECT_EQ(e.vendor[0], od::kDefaultMasterNode);
  EXPECT_EQ(io.count_of(Event::kHeartbeatMissed), 1u);
  EXPECT_EQ(j.drive.state, DriveState::kQuickStopActive);
  EXPECT_EQ(j.drive.statusword() & 0x6F, 0x07);
  EXPECT_EQ(j.error_register(), od::kErrorRegisterCommunication);
  // The ramp: 1 rad/s at 100 rad/s² stops in 10 ms, 5 mrad further.
  bool still = false;
  const double rad = j.ramp_period(&still);
  EXPECT_TRUE(still);
  EXPECT_EQ(j.drive.motion.demand_counts, 15'000);
  EXPECT_DOUBLE_EQ(rad, 0.015);
  EXPECT_EQ(j.drive.state, DriveState::kSwitchOnDisabled) << "0x605A = 2";
  EXPECT_EQ(j.drive.statusword() & 0x4F, 0x40);
  // The controller back: the communication error clears.
  j.on_heartbeat({od::kDefaultMasterNode, NmtState::kOperational}, &io);
  EXPECT_EQ(j.error_register(), 0);
}

// A killed controller stops its SYNCs with its heartbeat: the joint holds its last target
// (CSP), and by the time the heartbeat is missed it stands still; the quick stop leaves it
// there and switches it off.
TEST(JointSafety, AJointWithoutNewTargetsForAPeriodStandsStillWhereItIs) {
  RecordingIo io;
  JointNode j = enabled_joint(&io);
  ASSERT_TRUE(j.consumer.configure(od::consumer_heartbeat_entry(127, 200)));
  j.drive.abort_connection = od::kAbortConnectionQuickStop;
  io.now = 1'000'000;
  j.on_heartbeat({127, NmtState::kOperational}, &io);
  follow(&j, 200'000, 1, &io);  // 20 rad/s in its last period
  ASSERT_TRUE(j.consumer_due(1'200'001, &io));
  EXPECT_EQ(j.drive.state, DriveState::kQuickStopActive);
  bool still = false;
  EXPECT_DOUBLE_EQ(j.ramp_period(&still), 0.2);
  EXPECT_TRUE(still) << "at rest already: standstill in the first period";
  EXPECT_EQ(j.drive.state, DriveState::kSwitchOnDisabled);
}

TEST(JointSafety, TheAbortConnectionOptionChoosesTheReaction) {
  for (const int16_t option : {0, 1, 2, 3}) {
    RecordingIo io;
    JointNode j = enabled_joint(&io);
    uint32_t abort = 0;
    ASSERT_TRUE(write(&j, od::kConsumerHeartbeatTime, 1, od::consumer_heartbeat_entry(127, 100),
                      &abort, &io));
    ASSERT_TRUE(
        write(&j, od::kAbortConnectionOption, 0, static_cast<uint16_t>(option), &abort, &io));
    j.on_heartbeat({127, NmtState::kOperational}, &io);
    ASSERT_TRUE(j.consumer_due(100'001, &io));
    const DriveState expected[] = {DriveState::kOperationEnabled, DriveState::kFaultReactionActive,
                                   DriveState::kSwitchOnDisabled, DriveState::kQuickStopActive};
    EXPECT_EQ(j.drive.state, expected[option]) << "0x6007 = " << option;
    EXPECT_EQ(io.count_of(Event::kEmcySent), 1u) << "one EMCY, 0x8130, whatever the reaction";
  }
}

TEST(JointSafety, QuickStopOptionCodes) {
  RecordingIo io;
  uint32_t abort = 0;
  {  // 6: ramp, then stay in quick stop active; enable operation goes on from there.
    JointNode j = enabled_joint(&io);
    ASSERT_TRUE(write(&j, od::kQuickStopOptionCode, 0, 6, &abort, &io));
    follow(&j, 50'000, 1, &io);
    j.on_command({j.id, cia402::kCwQuickStop, 50'000}, &io);
    EXPECT_EQ(j.drive.state, DriveState::kQuickStopActive);
    bool still = false;
    int periods = 0;
    while (!still && periods < 1000) {
      j.ramp_period(&still);
      ++periods;
    }
    EXPECT_EQ(j.drive.state, DriveState::kQuickStopActive);
    EXPECT_FALSE(j.ramping());
    EXPECT_NE(j.drive.statusword() & cia402::kSwTargetReached, 0) << "standstill reached";
    j.on_command({j.id, cia402::kCwEnableOperation, 0}, &io);
    EXPECT_EQ(j.drive.state, DriveState::kOperationEnabled);
  }
  {  // 0: disable drive at once, no ramp.
    JointNode j = enabled_joint(&io);
    ASSERT_TRUE(write(&j, od::kQuickStopOptionCode, 0, 0, &abort, &io));
    follow(&j, 50'000, 1, &io);
    j.on_command({j.id, cia402::kCwQuickStop, 50'000}, &io);
    EXPECT_EQ(j.drive.state, DriveState::kSwitchOnDisabled);
    EXPECT_FALSE(j.ramping());
  }
  JointNode j = enabled_joint(&io);
  for (const uint32_t bad : {3u, 4u, 7u, 8u, 0xFFFFu}) {
    EXPECT_FALSE(write(&j, od::kQuickStopOptionCode, 0, bad, &abort, &io)) << bad;
  }
  EXPECT_EQ(abort, kSdoAbortValueRange);
}

TEST(JointSafety, FollowingErrorRaisesEmcyAndTheFaultReaction) {
  RecordingIo io;
  JointNode j = enabled_joint(&io);
  uint32_t abort = 0;
  ASSERT_TRUE(write(&j, od::kFollowingErrorWindow, 0, 1000, &abort, &io));
  ASSERT_TRUE(write(&j, od::kFollowingErrorTimeOut, 0, 20, &abort, &io));
  // The joint lags: it reaches only half of each step.
  for (int i = 1; i <= 4 && j.drive.state == DriveState::kOperationEnabled; ++i) {
    j.on_command({j.id, cia402::kCwEnableOperation, 10'000 * i}, &io);
    j.angle_at_sync_rad(0, &io);
    j.after_step(5'000 * i, &io);
  }
  EXPECT_EQ(io.count_of(Event::kFollowingError), 1u);
  ASSERT_EQ(io.frames.size(), 1u);
  Emergency e;
  ASSERT_EQ(decode_emcy(io.frames[0], &e), CodecStatus::kOk);
  EXPECT_EQ(e.error_code, od::kEmcyFollowingError);
  EXPECT_EQ(e.error_register & od::kErrorRegisterGeneric, od::kErrorRegisterGeneric);
  EXPECT_EQ(j.drive.state, DriveState::kFaultReactionActive) << "0x605E = 2: the ramp first";
  bool still = false;
  for (int i = 0; i < 1000 && !still; ++i) j.ramp_period(&still);
  EXPECT_EQ(j.drive.state, DriveState::kFault);
  uint32_t v = 0;
  ASSERT_TRUE(read(&j, od::kErrorRegister, 0, &v, &io));
  EXPECT_EQ(v, od::kErrorRegisterGeneric);
}

TEST(JointSafety, ObjectsAreWrittenReadBackAndRangeChecked) {
  RecordingIo io;
  JointNode j = enabled_joint(&io);
  uint32_t v = 0, abort = 0;
  struct Case {
    uint16_t index;
    uint8_t sub;
    uint32_t power_on, value, bad;
  };
  const Case cases[] = {
      {od::kConsumerHeartbeatTime, 1, 0, 0x007F00C8, 0x017F00C8},
      {od::kAbortConnectionOption, 0, 1, 3, 4},
      {od::kAbortConnectionOption, 0, 3, 3, 0xFFFF},  // −1: manufacturer-specific, none here
      {od::kQuickStopOptionCode, 0, 2, 2, 3},
      {od::kFaultReactionOptionCode, 0, 2, 2, 3},
      {od::kQuickStopDeceleration, 0, od::kPowerOnQuickStopDecelCounts, 5'000'000, 0},
      {od::kMaxProfileVelocity, 0, 0xFFFFFFFF, od::kConfigMaxVelocityCounts, 0},
      {od::kMaxMotorSpeed, 0, 0xFFFFFFFF, od::kConfigMaxVelocityCounts, 0},
      {od::kSoftwarePositionLimit, 1, static_cast<uint32_t>(-kRange), static_cast<uint32_t>(-1000),
       static_cast<uint32_t>(-kRange - 1)},
      {od::kSoftwarePositionLimit, 2, kRange, 1000, kRange + 1},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << std::hex << "0x" << c.index << "." << int(c.sub));
    ASSERT_TRUE(read(&j, c.index, c.sub, &v, &io));
    EXPECT_EQ(v, c.power_on);
    EXPECT_FALSE(write(&j, c.index, c.sub, c.bad, &abort, &io));
    EXPECT_EQ(abort, kSdoAbortValueRange);
    ASSERT_TRUE(write(&j, c.index, c.sub, c.value, &abort, &io));
    ASSERT_TRUE(read(&j, c.index, c.sub, &v, &io));
    EXPECT_EQ(v, c.value);
    EXPECT_FALSE(write(&j, c.index, 9, c.value, &abort, &io));
    EXPECT_EQ(abort, kSdoAbortNoSubindex);
    // Restore the power-on value where the next cases depend on it.
    if (c.index == od::kSoftwarePositionLimit) {
      ASSERT_TRUE(write(&j, c.index, c.sub, c.power_on, &abort, &io));
    }
  }
  // Following error window and time take any value (0xFFFFFFFF: off).
  ASSERT_TRUE(read(&j, od::kFollowingErrorWindow, 0, &v, &io));
  EXPECT_EQ(v, od::kFollowingErrorOff);
  ASSERT_TRUE(write(&j, od::kFollowingErrorTimeOut, 0, 20, &abort, &io));
  ASSERT_TRUE(read(&j, od::kFollowingErrorTimeOut, 0, &v, &io));
  EXPECT_EQ(v, 20u);
  // min above max is refused.
  ASSERT_TRUE(write(&j, od::kSoftwarePositionLimit, 2, 1000, &abort, &io));
  EXPECT_FALSE(write(&j, od::kSoftwarePositionLimit, 1, 2000, &abort, &io));
  EXPECT_EQ(abort, kSdoAbortValueRange);
  ASSERT_TRUE(read(&j, od::kSoftwarePositionLimit, 0, &v, &io));
  EXPECT_EQ(v, 2u);
  ASSERT_TRUE(read(&j, od::kConsumerHeartbeatTime, 0, &v, &io));
  EXPECT_EQ(v, 1u);
  EXPECT_FALSE(write(&j, od::kConsumerHeartbeatTime, 0, 1, &abort, &io));
  EXPECT_EQ(abort, kSdoAbortReadOnly);
}

TEST(JointSafety, IdentityAsCia301AndCia402Say) {
  RecordingIo io;
  JointNode j = enabled_joint(&io);
  uint32_t v = 0, abort = 0;
  ASSERT_TRUE(read(&j, od::kDeviceType, 0, &v, &io));
  EXPECT_EQ(v, 0x00020192u) << "CiA 402, servo drive";
  EXPECT_FALSE(write(&j, od::kDeviceType, 0, 0, &abort, &io));
  EXPECT_EQ(abort, kSdoAbortReadOnly);
  EXPECT_FALSE(read(&j, od::kDeviceType, 1, &v, &io));
  EXPECT_EQ(v, kSdoAbortNoSubindex);
  ASSERT_TRUE(read(&j, od::kErrorRegister, 0, &v, &io));
  EXPECT_EQ(v, 0u);
  ASSERT_TRUE(read(&j, od::kIdentity, 0, &v, &io));
  EXPECT_EQ(v, 4u);
  ASSERT_TRUE(read(&j, od::kIdentity, od::kIdentityVendorSub, &v, &io));
  EXPECT_EQ(v, od::kVendorId);
  ASSERT_TRUE(read(&j, od::kIdentity, od::kIdentityProductSub, &v, &io));
  EXPECT_EQ(v, od::kProductCodeJoint);
  ASSERT_TRUE(read(&j, od::kIdentity, od::kIdentityRevisionSub, &v, &io));
  EXPECT_EQ(v, od::kRevisionNumber);
  ASSERT_TRUE(read(&j, od::kIdentity, od::kIdentitySerialSub, &v, &io));
  EXPECT_EQ(v, od::serial_number(2));
  EXPECT_FALSE(read(&j, od::kIdentity, 5, &v, &io));
  EXPECT_EQ(v, kSdoAbortNoSubindex);
  EXPECT_FALSE(write(&j, od::kIdentity, 4, 1, &abort, &io));
  EXPECT_EQ(abort, kSdoAbortReadOnly);
  ASSERT_TRUE(read(&j, od::kSupportedDriveModes, 0, &v, &io));
  EXPECT_EQ(v, 0x00000080u) << "bit 7: cyclic synchronous position";
  EXPECT_FALSE(write(&j, od::kSupportedDriveModes, 0, 0xFF, &abort, &io));
  EXPECT_EQ(abort, kSdoAbortReadOnly);
  j.fault(od::kEmcyFollowingError, &io);
  ASSERT_TRUE(read(&j, od::kErrorRegister, 0, &v, &io));
  EXPECT_EQ(v & od::kErrorRegisterGeneric, od::kErrorRegisterGeneric) << "in fault";
}

TEST(ArmNodeSetSafety, EveryNodeHasItsIdentityAndAddressedNmtReachesOneNode) {
  RecordingIo io;
  ArmNodeSet nodes;
  nodes.power_on(kRange, &io);
  uint32_t serials[8] = {};
  for (int n = 0; n < 8; ++n) {
    const uint8_t id = n < 7 ? static_cast<uint8_t>(n + 1) : kCameraNode;
    const int32_t counts[7] = {};
    CameraNode::EpisodeStart start;
    SdoMessage answer;
    ASSERT_TRUE(nodes.on_sdo(sdo_request(SdoKind::kUploadRequest, id, od::kDeviceType, 0), counts,
                             &io, &start, &answer));
    EXPECT_EQ(answer.value, id == kCameraNode ? od::kDeviceTypeCamera : od::kDeviceTypeServoDrive);
    ASSERT_TRUE(nodes.on_sdo(
        sdo_request(SdoKind::kUploadRequest, id, od::kIdentity, od::kIdentitySerialSub), counts,
        &io, &start, &answer));
    serials[n] = answer.value;
    for (int k = 0; k < n; ++k) {
      EXPECT_NE(serials[k], serials[n]) << "serials differ per node";
    }
    ASSERT_TRUE(nodes.on_sdo(sdo_request(SdoKind::kUploadRequest, id, od::kSupportedDriveModes, 0),
                             counts, &io, &start, &answer));
    EXPECT_EQ(answer.kind, id == kCameraNode ? SdoKind::kNodeAbort : SdoKind::kUploadResponse);
  }
  nodes.on_nmt({NmtCommand::kStart, 4}, &io);
  for (int j = 0; j < 7; ++j) {
    EXPECT_EQ(nodes.joints[j].nmt, j == 3 ? NmtState::kOperational : NmtState::kPreOperational);
  }
  EXPECT_EQ(nodes.camera.nmt, NmtState::kPreOperational);
  nodes.on_nmt({NmtCommand::kResetCommunication, 4}, &io);
  EXPECT_EQ(nodes.joints[3].nmt, NmtState::kPreOperational);
}

TEST(ArmNodeSetSafety, ConsumersWakeTheOwnerAndEveryJointReacts) {
  RecordingIo io;
  ArmNodeSet nodes;
  nodes.power_on(kRange, &io);
  EXPECT_EQ(nodes.next_heartbeat_due_us(), UINT64_MAX) << "power-on: no consumer";
  for (JointNode& j : nodes.joints) {
    ASSERT_TRUE(j.consumer.configure(od::consumer_heartbeat_entry(127, 200)));
    j.drive.abort_connection = od::kAbortConnectionQuickStop;
  }
  io.now = 500'000;
  nodes.on_heartbeat({127, NmtState::kOperational}, &io);
  EXPECT_EQ(nodes.next_heartbeat_due_us(), 700'001u);
  io.clear();
  nodes.heartbeats_due(700'001, &io);
  EXPECT_EQ(io.count_of(Event::kHeartbeatMissed), 7u);
  EXPECT_EQ(io.frames.size(), 7u) << "one EMCY 0x8130 per joint";
  EXPECT_EQ(nodes.next_heartbeat_due_us(), UINT64_MAX);
}
