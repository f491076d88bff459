// CANopen codec: round trips of every message Curio uses, and malformed frames (bad DLC,
// wrong format, unknown ids, foreign node ids, unknown commands) rejected with the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/canopen.hpp"
#include "firmware/protocol/cia402.hpp"

using namespace curio::protocol;
using curio::hal::CanFrame;
namespace hal = curio::hal;

TEST(CanOpen, NmtSyncHeartbeatEmcyRoundTrip) {
  NmtMessage nmt{NmtCommand::kStart, 0}, nmt_out;
  CanFrame f = encode_nmt(nmt);
  EXPECT_EQ(f.id, 0x000u);
  EXPECT_EQ(f.len, 2);
  ASSERT_EQ(decode_nmt(f, &nmt_out), CodecStatus::kOk);
  EXPECT_EQ(nmt_out.command, NmtCommand::kStart);
  EXPECT_EQ(nmt_out.node, 0);
  ASSERT_EQ(decode_nmt(encode_nmt({NmtCommand::kResetNode, 7}), &nmt_out), CodecStatus::kOk);
  EXPECT_EQ(nmt_out.node, 7);

  uint8_t counter = 0;
  ASSERT_EQ(decode_sync(encode_sync(240), &counter), CodecStatus::kOk);
  EXPECT_EQ(counter, 240);
  CanFrame bare;
  bare.id = 0x080;
  ASSERT_EQ(decode_sync(bare, &counter), CodecStatus::kOk) << "SYNC without counter";
  EXPECT_EQ(counter, 0);

  Heartbeat hb{3, NmtState::kOperational}, hb_out;
  f = encode_heartbeat(hb);
  EXPECT_EQ(f.id, 0x703u);
  ASSERT_EQ(decode_heartbeat(f, &hb_out), CodecStatus::kOk);
  EXPECT_EQ(hb_out.node, 3);
  EXPECT_EQ(hb_out.state, NmtState::kOperational);

  Emergency e{kCameraNode, 0x8611, 0x81, {1, 2, 3, 4, 5}}, e_out;
  f = encode_emcy(e);
  EXPECT_EQ(f.id, 0x0A0u);
  ASSERT_EQ(decode_emcy(f, &e_out), CodecStatus::kOk);
  EXPECT_EQ(e_out.error_code, 0x8611);
  EXPECT_EQ(e_out.error_register, 0x81);
  EXPECT_EQ(e_out.vendor[4], 5);
}

TEST(CanOpen, ExpeditedSdoEveryKindAndSize) {
  for (uint8_t size = 1; size <= 4; ++size) {
    SdoMessage m{SdoKind::kDownloadRequest, 2, cia402::kModesOfOperation, 0, 0x12345608u, size};
    CanFrame f = encode_sdo(m);
    EXPECT_EQ(f.id, 0x602u);
    EXPECT_EQ(f.data[0], static_cast<uint8_t>(0x23 | ((4 - size) << 2)));
    SdoMessage out;
    ASSERT_EQ(decode_sdo(f, &out), CodecStatus::kOk);
    EXPECT_EQ(out.kind, SdoKind::kDownloadRequest);
    EXPECT_EQ(out.size, size);
    EXPECT_EQ(out.index, 0x6060);
    const uint32_t mask = size == 4 ? 0xFFFFFFFFu : (1u << (8 * size)) - 1u;
    EXPECT_EQ(out.value, 0x12345608u & mask);

    m.kind = SdoKind::kUploadResponse;
    f = encode_sdo(m);
    EXPECT_EQ(f.id, 0x582u);
    ASSERT_EQ(decode_sdo(f, &out), CodecStatus::kOk);
    EXPECT_EQ(out.kind, SdoKind::kUploadResponse);
    EXPECT_EQ(out.value, 0x12345608u & mask);
  }
  const std::pair<SdoKind, uint32_t> others[] = {{SdoKind::kUploadRequest, 0x601},
                                                 {SdoKind::kDownloadResponse, 0x581},
                                                 {SdoKind::kClientAbort, 0x601},
                                                 {SdoKind::kNodeAbort, 0x581}};
  for (const auto& [kind, id] : others) {
    SdoMessage m{kind, 1, 0x6041, 0, kSdoAbortNoObject, 4}, out;
    CanFrame f = encode_sdo(m);
    EXPECT_EQ(f.id, id);
    ASSERT_EQ(decode_sdo(f, &out), CodecStatus::kOk);
    EXPECT_EQ(out.kind, kind);
    EXPECT_EQ(out.index, 0x6041);
    if (kind == SdoKind::kClientAbort || kind == SdoKind::kNodeAbort) {
      EXPECT_EQ(out.value, kSdoAbortNoObject);
    }
  }
}

TEST(CanOpen, MalformedFramesAreRejectedWithTheReason) {
  // Bad DLC.
  CanFrame f = encode_joint_command({1, cia402::kCwEnableOperation, 42});
  f.len = 5;
  JointCommand jc;
  EXPECT_EQ(decode_joint_command(f, &jc), CodecStatus::kBadLength);
  f.len = 8;
  EXPECT_EQ(decode_joint_command(f, &jc), CodecStatus::kBadLength);
  CanFrame sdo = encode_sdo({SdoKind::kUploadRequest, 1, 0x6064, 0, 0, 4});
  sdo.len = 7;
  SdoMessage sm;
  EXPECT_EQ(decode_sdo(sdo, &sm), CodecStatus::kBadLength);
  CanFrame hb = encode_heartbeat({1, NmtState::kOperational});
  hb.len = 0;
  Heartbeat h;
  EXPECT_EQ(decode_heartbeat(hb, &h), CodecStatus::kBadLength);
  CanFrame sync = encode_sync(1);
  sync.len = 2;
  uint8_t c;
  EXPECT_EQ(decode_sync(sync, &c), CodecStatus::kBadLength);

  // Wrong format: FD, 29-bit, remote.
  f = encode_joint_command({1, 0, 0});
  f.flags = hal::kFlagFd;
  EXPECT_EQ(decode_joint_command(f, &jc), CodecStatus::kBadFormat);
  f.flags = hal::kFlagExtended;
  EXPECT_EQ(decode_joint_command(f, &jc), CodecStatus::kBadFormat);
  f.flags = hal::kFlagRemote;
  EXPECT_EQ(decode_joint_command(f, &jc), CodecStatus::kBadFormat);

  // Unknown ids / other messages.
  f = encode_joint_feedback({1, 0, 0});
  EXPECT_EQ(decode_joint_command(f, &jc), CodecStatus::kWrongId);
  CanFrame nmt = encode_nmt({NmtCommand::kStart, 0});
  nmt.id = 0x001;
  NmtMessage nm;
  EXPECT_EQ(decode_nmt(nmt, &nm), CodecStatus::kWrongId);
  CanFrame base;
  base.id = 0x200;  // RPDO1 base without a node
  base.len = 6;
  EXPECT_EQ(decode_joint_command(base, &jc), CodecStatus::kWrongId);

  // Foreign node ids.
  for (uint8_t node : {8, 0x1F, 0x21, 0x7F}) {
    f = encode_joint_command({node, 0, 0});
    EXPECT_EQ(decode_joint_command(f, &jc), CodecStatus::kForeignNode) << int(node);
  }
  f = encode_joint_command({kCameraNode, 0, 0});
  EXPECT_EQ(decode_joint_command(f, &jc), CodecStatus::kForeignNode)
      << "the camera has no joint PDO";
  EXPECT_EQ(decode_heartbeat(encode_heartbeat({9, NmtState::kOperational}), &h),
            CodecStatus::kForeignNode);
  EXPECT_EQ(decode_nmt(encode_nmt({NmtCommand::kStart, 9}), &nm), CodecStatus::kForeignNode);
  sdo = encode_sdo({SdoKind::kUploadRequest, 0x40, 0x6064, 0, 0, 4});
  EXPECT_EQ(decode_sdo(sdo, &sm), CodecStatus::kForeignNode);

  // Unknown commands and unsupported transfers.
  nmt = encode_nmt({NmtCommand::kStart, 0});
  nmt.data[0] = 0x03;
  EXPECT_EQ(decode_nmt(nmt, &nm), CodecStatus::kBadCommand);
  hb.len = 1;
  hb.data[0] = 0x33;
  EXPECT_EQ(decode_heartbeat(hb, &h), CodecStatus::kBadCommand);
  sdo = encode_sdo({SdoKind::kDownloadRequest, 1, 0x6060, 0, 8, 1});
  sdo.data[0] = 0x21;  // segmented download
  EXPECT_EQ(decode_sdo(sdo, &sm), CodecStatus::kUnsupported);
  sdo.data[0] = 0xC0;  // block upload
  EXPECT_EQ(decode_sdo(sdo, &sm), CodecStatus::kUnsupported);
  sdo.data[0] = 0xE0;  // ccs 7
  EXPECT_EQ(decode_sdo(sdo, &sm), CodecStatus::kBadCommand);
  sync = encode_sync(241);
  EXPECT_EQ(decode_sync(sync, &c), CodecStatus::kOutOfRange);
}

TEST(Cia402, StatuswordStatesFollowTheProfileMasks) {
  using cia402::DriveState;
  const std::pair<uint16_t, DriveState> cases[] = {
      {0x0000, DriveState::kNotReadyToSwitchOn},
      {0x0040, DriveState::kSwitchOnDisabled},
      {0x0021, DriveState::kReadyToSwitchOn},
      {0x0023, DriveState::kSwitchedOn},
      {0x0027, DriveState::kOperationEnabled},
      {0x0007, DriveState::kQuickStopActive},
      {0x000F, DriveState::kFaultReactionActive},
      {0x0008, DriveState::kFault},
      // Bits outside the masks (remote, target reached, following, voltage) do not matter.
      {0x1637, DriveState::kOperationEnabled},
      {0x0218, DriveState::kFault},
      {0x0250, DriveState::kSwitchOnDisabled},
      {0x0031, DriveState::kReadyToSwitchOn}};
  for (const auto& [sw, state] : cases) {
    EXPECT_EQ(cia402::decode_state(sw), state) << std::hex << sw;
  }
  for (auto s : {DriveState::kSwitchOnDisabled, DriveState::kReadyToSwitchOn,
                 DriveState::kSwitchedOn, DriveState::kOperationEnabled, DriveState::kFault}) {
    EXPECT_EQ(cia402::decode_state(cia402::statusword_for(s)), s);
  }
  EXPECT_EQ((0x0027 & 0x6F), 0x27);
}

TEST(ArmMessages, JointPdosRoundTrip) {
  for (uint8_t node = 1; node <= 7; ++node) {
    JointCommand c{node, cia402::kCwEnableOperation, -3141593}, c_out;
    CanFrame f = encode_joint_command(c);
    EXPECT_EQ(f.id, 0x200u + node);
    EXPECT_EQ(f.len, 6);
    ASSERT_EQ(decode_joint_command(f, &c_out), CodecStatus::kOk);
    EXPECT_EQ(c_out.node, node);
    EXPECT_EQ(c_out.controlword, 0x000F);
    EXPECT_EQ(c_out.target_counts, -3141593);
    JointFeedback fb{node, 0x1637, INT32_MIN}, fb_out;
    f = encode_joint_feedback(fb);
    EXPECT_EQ(f.id, 0x180u + node);
    ASSERT_EQ(decode_joint_feedback(f, &fb_out), CodecStatus::kOk);
    EXPECT_EQ(fb_out.statusword, 0x1637);
    EXPECT_EQ(fb_out.actual_counts, INT32_MIN);
  }
  // Little-endian layout: controlword first, then the position.
  CanFrame f = encode_joint_command({1, 0x000F, 0x01020304});
  const uint8_t expect[6] = {0x0F, 0x00, 0x04, 0x03, 0x02, 0x01};
  EXPECT_TRUE(std::equal(expect, expect + 6, f.data));
}

TEST(ArmMessages, PositionUnitsRoundHalfAwayFromZeroAndDecodeExactly) {
  int32_t c = 0;
  EXPECT_EQ(angle_to_counts(M_PI, &c), CodecStatus::kOk);
  EXPECT_EQ(c, 3141593);
  angle_to_counts(-M_PI, &c);
  EXPECT_EQ(c, -3141593);
  angle_to_counts(1e-6, &c);
  EXPECT_EQ(c, 1);
  // 0.25 µrad steps: x·1e6 is exact in double for these, so the tie rule shows.
  angle_to_counts(2.5e-6 * 1.0, &c);
  EXPECT_EQ(c, std::round(2.5e-6 * 1e6));
  angle_to_counts(0.0000015, &c);
  EXPECT_EQ(c, static_cast<int32_t>(std::round(0.0000015 * 1e6)));
  angle_to_counts(-0.5 / 1e6 * 1.0, &c);
  EXPECT_EQ(c, static_cast<int32_t>(std::round(-0.5 / 1e6 * 1e6)));
  angle_to_counts(-0.0, &c);
  EXPECT_EQ(c, 0);
  EXPECT_EQ(angle_to_counts(2147.483647, &c), CodecStatus::kOk);
  EXPECT_EQ(c, INT32_MAX);
  EXPECT_EQ(angle_to_counts(2147.5, &c), CodecStatus::kOutOfRange);
  EXPECT_EQ(c, INT32_MAX);
  EXPECT_EQ(angle_to_counts(-1e9, &c), CodecStatus::kOutOfRange);
  EXPECT_EQ(c, INT32_MIN);
  EXPECT_EQ(angle_to_counts(std::numeric_limits<double>::quiet_NaN(), &c),
            CodecStatus::kOutOfRange);
  EXPECT_EQ(c, 0);
  // Decode then encode is the identity on counts: the bus loses nothing twice.
  for (int32_t k : {0, 1, -1, 500000, 3141593, -3141593, 22000000, INT32_MAX, INT32_MIN + 1}) {
    int32_t back = 0;
    ASSERT_EQ(angle_to_counts(counts_to_angle(k), &back), CodecStatus::kOk) << k;
    EXPECT_EQ(back, k);
    EXPECT_EQ(counts_to_angle(k), static_cast<double>(k) / 1e6);
  }
  uint64_t x = 88172645463325252ull;
  for (int i = 0; i < 100000; ++i) {  // xorshift sweep over the arm's angle range
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    const double angle = (static_cast<double>(x % 44000001) - 22000000.0) * 1e-6 + 1e-7 * (x % 7);
    angle_to_counts(angle, &c);
    ASSERT_LE(std::fabs(counts_to_angle(c) - angle), 0.5e-6 + 1e-12);
    int32_t back = 0;
    angle_to_counts(counts_to_angle(c), &back);
    ASSERT_EQ(back, c);
  }
}

TEST(ArmMessages, CameraPixelQuantization) {
  EXPECT_EQ(camera_pixel(0.0), 0);
  EXPECT_EQ(camera_pixel(1.0), 255);
  EXPECT_EQ(camera_pixel(0.5), 128) << "127.5 rounds away from zero";
  EXPECT_EQ(camera_pixel(0.2), 51);
  EXPECT_EQ(camera_pixel(-0.1), 0);
  EXPECT_EQ(camera_pixel(1.5), 255);
  EXPECT_EQ(camera_pixel(std::numeric_limits<double>::quiet_NaN()), 0);
}

TEST(ArmMessages, CameraCaptureAndGroundTruthRoundTrip) {
  CameraCapture cc{123456}, cc_out;
  CanFrame f = encode_camera_capture(cc);
  EXPECT_EQ(f.id, 0x220u);
  ASSERT_EQ(decode_camera_capture(f, &cc_out), CodecStatus::kOk);
  EXPECT_EQ(cc_out.episode, 123456u);

  GroundTruth g{9666, true, 0.6, -0.0, 0.7 + 1e-17, std::numeric_limits<double>::denorm_min()},
      g_out;
  f = encode_ground_truth(g);
  EXPECT_EQ(f.id, 0x2A0u);
  EXPECT_TRUE(f.fd());
  EXPECT_EQ(f.len, 48);
  ASSERT_EQ(decode_ground_truth(f, &g_out), CodecStatus::kOk);
  EXPECT_EQ(g_out.episode, 9666u);
  EXPECT_TRUE(g_out.ball_grasped);
  EXPECT_EQ(std::bit_cast<uint64_t>(g_out.ball_x), std::bit_cast<uint64_t>(0.6));
  EXPECT_TRUE(std::signbit(g_out.ball_y)) << "bit for bit, negative zero included";
  EXPECT_EQ(g_out.distractor_x, g.distractor_x);
  EXPECT_EQ(g_out.distractor_y, g.distractor_y);
  CanFrame classic = f;
  classic.flags = 0;
  EXPECT_EQ(decode_ground_truth(classic, &g_out), CodecStatus::kBadFormat);
  CanFrame short_gt = f;
  short_gt.len = 32;
  EXPECT_EQ(decode_ground_truth(short_gt, &g_out), CodecStatus::kBadLength);
  f.data[4] = 0x02;
  EXPECT_EQ(decode_ground_truth(f, &g_out), CodecStatus::kOutOfRange);
}

// The classic profile: the same values bit for bit in five 8-byte frames 0x2A1..0x2A5, and
// an assembler that takes either profile and drops a message whose parts come out of order.
TEST(ArmMessages, GroundTruthInClassicFramesCarriesTheSameValues) {
  const GroundTruth g{9666, true, 0.6, -0.0, 0.7 + 1e-17,
                      std::numeric_limits<double>::denorm_min()};
  CanFrame frames[kGroundTruthClassicFrames];
  ASSERT_EQ(encode_ground_truth(g, CanProfile::kClassic, frames), kGroundTruthClassicFrames);
  for (size_t i = 0; i < kGroundTruthClassicFrames; ++i) {
    EXPECT_EQ(frames[i].id, 0x2A1u + i);
    EXPECT_FALSE(frames[i].fd() || frames[i].extended());
    EXPECT_EQ(frames[i].len, 8);
    uint8_t node = 0;
    EXPECT_EQ(classify(frames[i], &node), MessageKind::kGroundTruth);
    EXPECT_EQ(node, kCameraNode);
  }
  GroundTruthAssembler a;
  GroundTruth out;
  bool complete = false;
  for (size_t i = 0; i < kGroundTruthClassicFrames; ++i) {
    ASSERT_EQ(a.on_frame(frames[i], &out, &complete), CodecStatus::kOk);
    EXPECT_EQ(complete, i + 1 == kGroundTruthClassicFrames);
  }
  EXPECT_EQ(out.episode, 9666u);
  EXPECT_TRUE(out.ball_grasped);
  EXPECT_EQ(std::bit_cast<uint64_t>(out.ball_x), std::bit_cast<uint64_t>(g.ball_x));
  EXPECT_TRUE(std::signbit(out.ball_y));
  EXPECT_EQ(std::bit_cast<uint64_t>(out.distractor_x), std::bit_cast<uint64_t>(g.distractor_x));
  EXPECT_EQ(std::bit_cast<uint64_t>(out.distractor_y), std::bit_cast<uint64_t>(g.distractor_y));

  // The FD profile: one frame, the same assembler.
  CanFrame fd[kGroundTruthClassicFrames];
  ASSERT_EQ(encode_ground_truth(g, CanProfile::kFd, fd), 1u);
  GroundTruth out_fd;
  ASSERT_EQ(a.on_frame(fd[0], &out_fd, &complete), CodecStatus::kOk);
  EXPECT_TRUE(complete);
  EXPECT_EQ(std::bit_cast<uint64_t>(out_fd.distractor_y), std::bit_cast<uint64_t>(g.distractor_y));

  // A part without its header, a part skipped, a reserved flag, a wrong length: refused, and
  // the message in progress is dropped (no values from two messages are ever mixed).
  EXPECT_EQ(a.on_frame(frames[2], &out, &complete), CodecStatus::kBadCommand);
  ASSERT_EQ(a.on_frame(frames[0], &out, &complete), CodecStatus::kOk);
  ASSERT_EQ(a.on_frame(frames[1], &out, &complete), CodecStatus::kOk);
  EXPECT_EQ(a.on_frame(frames[3], &out, &complete), CodecStatus::kBadCommand);
  EXPECT_EQ(a.on_frame(frames[4], &out, &complete), CodecStatus::kBadCommand);
  EXPECT_FALSE(complete);
  CanFrame bad = frames[0];
  bad.data[4] = 0x02;
  EXPECT_EQ(a.on_frame(bad, &out, &complete), CodecStatus::kOutOfRange);
  bad = frames[1];
  bad.len = 7;
  EXPECT_EQ(a.on_frame(bad, &out, &complete), CodecStatus::kBadLength);
  CanFrame other;
  other.id = 0x2A6;
  other.len = 8;
  EXPECT_EQ(a.on_frame(other, &out, &complete), CodecStatus::kWrongId);
  uint8_t node = 0;
  EXPECT_EQ(classify(other, &node), MessageKind::kUnknown);
}

// The camera image's ISO-TP links follow the profile: 64-byte FD frames or 8-byte classic.
TEST(ArmMessages, CameraLinksFollowTheProfile) {
  EXPECT_TRUE(camera_link_for_camera(CanProfile::kFd).fd);
  EXPECT_EQ(camera_link_for_camera(CanProfile::kFd).tx_dl, 64);
  EXPECT_FALSE(camera_link_for_camera(CanProfile::kClassic).fd);
  EXPECT_EQ(camera_link_for_camera(CanProfile::kClassic).tx_dl, 8);
  EXPECT_FALSE(camera_link_for_controller(CanProfile::kClassic).fd);
  EXPECT_EQ(profile_for(true), CanProfile::kFd);
  EXPECT_EQ(profile_for(false), CanProfile::kClassic);
}

TEST(ArmMessages, ClassifyNamesEveryMessageAndFlagsForeignNodes) {
  uint8_t node = 0;
  EXPECT_EQ(classify(encode_nmt({NmtCommand::kStart, 0}), &node), MessageKind::kNmt);
  EXPECT_EQ(classify(encode_sync(1), &node), MessageKind::kSync);
  EXPECT_EQ(classify(encode_joint_command({4, 0, 0}), &node), MessageKind::kJointCommand);
  EXPECT_EQ(node, 4);
  EXPECT_EQ(classify(encode_joint_feedback({7, 0, 0}), &node), MessageKind::kJointFeedback);
  EXPECT_EQ(classify(encode_joint_feedback({8, 0, 0}), &node), MessageKind::kForeign);
  EXPECT_EQ(classify(encode_heartbeat({kCameraNode, NmtState::kBootUp}), &node),
            MessageKind::kHeartbeat);
  EXPECT_EQ(classify(encode_heartbeat({0x30, NmtState::kBootUp}), &node), MessageKind::kForeign);
  EXPECT_EQ(classify(encode_emcy({2, 0, 0, {}}), &node), MessageKind::kEmcy);
  EXPECT_EQ(classify(encode_sdo({SdoKind::kUploadRequest, 2, 0, 0, 0, 4}), &node),
            MessageKind::kSdoRequest);
  EXPECT_EQ(classify(encode_sdo({SdoKind::kNodeAbort, 2, 0, 0, 0, 4}), &node),
            MessageKind::kSdoResponse);
  EXPECT_EQ(classify(encode_camera_capture({1}), &node), MessageKind::kCameraCapture);
  EXPECT_EQ(classify(encode_ground_truth({}), &node), MessageKind::kGroundTruth);
  CanFrame img;
  img.id = kCameraImageId;
  img.flags = hal::kFlagExtended | hal::kFlagFd;
  EXPECT_EQ(classify(img, &node), MessageKind::kCameraImage);
  img.id = kCameraFlowControlId;
  EXPECT_EQ(classify(img, &node), MessageKind::kCameraFlowControl);
  img.id = 0x220;  // extended id equal to a CANopen id: not ours
  EXPECT_EQ(classify(img, &node), MessageKind::kUnknown);
  CanFrame unknown;
  unknown.id = 0x7E5;  // LSS
  EXPECT_EQ(classify(unknown, &node), MessageKind::kUnknown);
}
