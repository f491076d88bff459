// Curio's message map on top of CANopen: what the controller and the simulated arm say.
//   joints 1..7  RPDO1 0x200+n  controlword u16 | target position i32 (0x607A)   6 bytes
//                TPDO1 0x180+n  statusword u16  | actual position i32 (0x6064)   6 bytes
//   camera 0x20  RPDO1 0x220    capture request: episode u32                       4 bytes
//                TPDO2 0x2A0    ground truth (evaluation only), CAN FD            48 bytes
//                  classic: 0x2A1 episode | flags, 0x2A2..0x2A5 one float64 each  5 × 8 bytes
//                ISO-TP 0x18DAF120 → controller, flow control 0x18DA20F1 (29-bit, normal
//                fixed addressing: 0x18DA<target><source>, controller = 0xF1); FD frames of
//                64 bytes, or classic frames of 8 (TX_DL 8)
// Two profiles, one protocol: CanProfile::kFd (CAN FD) and kClassic (every frame a classic
// frame of at most 8 bytes, for classic-only drives, adapters and the kernel's slcan). The
// profile follows the bus (hal::CanBus::carries_fd()); the joints' frames are the same in both,
// and the messages carry the same values, so results do not depend on the profile.
// Positions: 1 count = 1 µrad (1e-6 rad). Encoding rounds once, exactly as written in
// angle_to_counts; decoding is one IEEE division. The in-process path must quantize through
// the same two functions so that bus and in-process runs agree bit for bit.
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/protocol/canopen.hpp"
#include "firmware/protocol/isotp.hpp"

namespace curio::protocol {

// ---- profiles
enum class CanProfile : uint8_t {
  kFd = 0,   // CAN FD: ground truth in one 48-byte frame, ISO-TP with 64-byte frames
  kClassic,  // classic CAN: ground truth in five 8-byte frames, ISO-TP with 8-byte frames
};
constexpr CanProfile profile_for(bool bus_carries_fd) {
  return bus_carries_fd ? CanProfile::kFd : CanProfile::kClassic;
}
constexpr const char* to_string(CanProfile p) {
  return p == CanProfile::kFd ? "fd" : "classic";
}

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

// The ISO-TP links of the camera transfer, seen from each end, in `profile`'s frames.
IsoTpLink camera_link_for_camera(CanProfile profile);
IsoTpLink camera_link_for_controller(CanProfile profile);

struct CameraCapture {  // controller → camera: render the final state of `episode` and send it
  uint32_t episode = 0;
};
inline constexpr uint8_t kCameraCaptureBytes = 4;
CanFrame encode_camera_capture(const CameraCapture& c);
CodecStatus decode_camera_capture(const CanFrame& f, CameraCapture* out);

// Simulator → evaluation: where ball and distractor really ended (never an input to
// exploration). CAN FD, 48 bytes: episode u32 | flags u8 (bit 0 ball grasped) | 3 reserved |
// ball x, ball y, distractor x, distractor y as IEEE float64 little-endian | 8 reserved.
// Classic: the same values in five 8-byte frames sent in order, 0x2A1 episode u32 | flags u8 |
// 3 reserved, then 0x2A2 ball x, 0x2A3 ball y, 0x2A4 distractor x, 0x2A5 distractor y
// (float64 little-endian). Ids of their own, so one DBC describes both profiles. 0x2A1..0x2A5
// are the default TPDO2 ids of nodes 0x21..0x25, which a Curio bus does not have; the ground
// truth only exists where the arm is simulated.
struct GroundTruth {
  uint32_t episode = 0;
  bool ball_grasped = false;
  double ball_x = 0, ball_y = 0, distractor_x = 0, distractor_y = 0;
};
inline constexpr uint8_t kGroundTruthBytes = 48;
inline constexpr size_t kGroundTruthClassicFrames = 5;
inline constexpr uint32_t kCobGroundTruthClassic = kCobGroundTruth + 1;  // the header, 0x2A1
inline constexpr uint32_t kCobGroundTruthLast = kCobGroundTruthClassic + kGroundTruthClassicFrames - 1;
static_assert(kCobGroundTruthLast == 0x2A5);
// The FD frame.
CanFrame encode_ground_truth(const GroundTruth& g);
CodecStatus decode_ground_truth(const CanFrame& f, GroundTruth* out);
// The frames of `profile` into out[0..kGroundTruthClassicFrames); returns how many (1 or 5).
size_t encode_ground_truth(const GroundTruth& g, CanProfile profile,
                           CanFrame out[kGroundTruthClassicFrames]);

// Receives the ground truth in either profile: an FD frame is a whole message, the classic
// frames are assembled in order (a header restarts; a part out of order drops the message).
class GroundTruthAssembler {
 public:
  // kOk for a valid frame of the message; *complete says whether it completed one (then *out
  // holds it). Otherwise the decoders' status (kWrongId: not a ground-truth frame; kBadFormat,
  // kBadLength, kOutOfRange: malformed; kBadCommand: a part out of order) and the message in
  // progress is dropped.
  CodecStatus on_frame(const CanFrame& f, GroundTruth* out, bool* complete);
  void reset() { next_part_ = 0; }

 private:
  GroundTruth partial_;
  size_t next_part_ = 0;  // 0: waiting for a header; 1..4: the float64 expected next
};

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
