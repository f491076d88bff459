// Curio's message map on top of CANopen: what the controller and the simulated arm say.
//   joints 1..7  RPDO1 0x200+n  controlword u16 | target position i32 (0x607A)   6 bytes
//                TPDO1 0x180+n  statusword u16  | actual position i32 (0x6064)   6 bytes
//   camera 0x20  RPDO1 0x220    capture request: episode u32                       4 bytes
//                TPDO2 0x2A0    ground truth (evaluation only), CAN FD            48 bytes
//                ISO-TP 0x18DAF120 → controller, flow control 0x18DA20F1 (FD, 29-bit,
//                normal fixed addressing: 0x18DA<target><source>, controller = 0xF1)
// Positions: 1 count = 1 µrad (1e-6 rad). Encoding rounds once, exactly as written in
// angle_to_counts; decoding is one IEEE division. The in-process path must quantize through
// the same two functions so that bus and in-process runs agree bit for bit.
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/protocol/canopen.hpp"
#include "firmware/protocol/isotp.hpp"

namespace curio::protocol {

// ---- position units
inline constexpr double kCountsPerRad = 1e6;

// counts = round_half_away_from_zero(angle_rad * 1e6), the product rounded to double first.
// |angle| beyond int32 range (±2147.48 rad) or NaN → kOutOfRange (*counts saturated, NaN → 0).
CodecStatus angle_to_counts(double angle_rad, int32_t* counts);
// rad = counts / 1e6 (correctly rounded IEEE division).
constexpr double counts_to_angle(int32_t counts) {
  return static_cast<double>(counts) / kCountsPerRad;
}

// ---- joints (CiA 402 cyclic synchronous position)
struct JointCommand {  // RPDO1
  uint8_t node = kFirstJointNode;
  uint16_t controlword = 0;
  int32_t target_counts = 0;
};
struct JointFeedback {  // TPDO1
  uint8_t node = kFirstJointNode;
  uint16_t statusword = 0;
  int32_t actual_counts = 0;
};
inline constexpr uint8_t kJointPdoBytes = 6;
CanFrame encode_joint_command(const JointCommand& c);
CodecStatus decode_joint_command(const CanFrame& f, JointCommand* out);
CanFrame encode_joint_feedback(const JointFeedback& fb);
CodecStatus decode_joint_feedback(const CanFrame& f, JointFeedback* out);

// ---- camera node
inline constexpr uint32_t kCobCameraCapture = kCobRpdo1 + kCameraNode;  // 0x220
inline constexpr uint32_t kCobGroundTruth = kCobTpdo2 + kCameraNode;    // 0x2A0
inline constexpr uint8_t kControllerAddress = 0xF1;
inline constexpr uint32_t kCameraImageId = 0x18DA0000u | (kControllerAddress << 8) | kCameraNode;
inline constexpr uint32_t kCameraFlowControlId =
    0x18DA0000u | (kCameraNode << 8) | kControllerAddress;
static_assert(kCameraImageId == 0x18DAF120u && kCameraFlowControlId == 0x18DA20F1u);

// Image payload: 64 × 64 RGB, row-major (row 0 at the top), channels interleaved (HWC),
// one byte per channel: round(255 · v) for v in [0, 1] (see camera_pixel).
inline constexpr size_t kCameraWidth = 64, kCameraHeight = 64, kCameraChannels = 3;
inline constexpr size_t kCameraImageBytes = kCameraWidth * kCameraHeight * kCameraChannels;
static_assert(kCameraImageBytes == kIsoTpMaxMessage, "one camera frame fills the ISO-TP buffer");

// v in [0,1] → byte: round half away from zero of 255·v, clamped (NaN → 0).
uint8_t camera_pixel(double v);

// The ISO-TP links of the camera transfer, seen from each end.
IsoTpLink camera_link_for_camera();
IsoTpLink camera_link_for_controller();

struct CameraCapture {  // controller → camera: render the final state of `episode` and send it
  uint32_t episode = 0;
};
inline constexpr uint8_t kCameraCaptureBytes = 4;
CanFrame encode_camera_capture(const CameraCapture& c);
CodecStatus decode_camera_capture(const CanFrame& f, CameraCapture* out);

// Simulator → evaluation: where ball and distractor really ended (never an input to
// exploration). CAN FD, 48 bytes: episode u32 | flags u8 (bit 0 ball grasped) | 3 reserved |
// ball x, ball y, distractor x, distractor y as IEEE float64 little-endian | 8 reserved.
struct GroundTruth {
  uint32_t episode = 0;
  bool ball_grasped = false;
  double ball_x = 0, ball_y = 0, distractor_x = 0, distractor_y = 0;
};
inline constexpr uint8_t kGroundTruthBytes = 48;
CanFrame encode_ground_truth(const GroundTruth& g);
CodecStatus decode_ground_truth(const CanFrame& f, GroundTruth* out);

// ---- dispatch
enum class MessageKind : uint8_t {
  kNmt,
  kSync,
  kEmcy,
  kJointCommand,
  kJointFeedback,
  kSdoResponse,
  kSdoRequest,
  kHeartbeat,
  kCameraCapture,
  kGroundTruth,
  kCameraImage,
  kCameraFlowControl,
  kForeign,  // a known CANopen function code from a node that is not Curio's
  kUnknown,  // an identifier Curio does not use
};
// Which message a frame would be, by identifier and id width only (decode to validate).
MessageKind classify(const CanFrame& f, uint8_t* node);

}  // namespace curio::protocol
