#include "firmware/protocol/arm_messages.hpp"

#include <bit>
#include <cmath>

#include "firmware/protocol/bytes.hpp"

namespace curio::protocol {
namespace {

CodecStatus check_classic(const CanFrame& f, uint32_t id, uint8_t len) {
  if (f.id != id) return CodecStatus::kWrongId;
  if (f.extended() || f.fd() || f.remote() || f.error()) return CodecStatus::kBadFormat;
  return f.len == len ? CodecStatus::kOk : CodecStatus::kBadLength;
}

CodecStatus check_joint_pdo(const CanFrame& f, uint32_t base, uint8_t* node) {
  if (f.id <= base || f.id > base + 0x7F) return CodecStatus::kWrongId;
  if (f.extended() || f.fd() || f.remote() || f.error()) return CodecStatus::kBadFormat;
  *node = static_cast<uint8_t>(f.id - base);
  if (!is_joint_node(*node)) return CodecStatus::kForeignNode;
  return f.len == kJointPdoBytes ? CodecStatus::kOk : CodecStatus::kBadLength;
}

CanFrame pdo(uint32_t id, uint16_t word, int32_t position) {
  CanFrame f;
  f.id = id;
  f.len = kJointPdoBytes;
  put_le16(f.data, word);
  put_le32(f.data + 2, static_cast<uint32_t>(position));
  return f;
}

// The ground truth's parts shared by both profiles: the header (episode u32, flags u8 with
// bit 0 ball grasped, reserved bits zero) and the four float64 in wire order.
constexpr double GroundTruth::*kTruthValues[4] = {&GroundTruth::ball_x, &GroundTruth::ball_y,
                                                   &GroundTruth::distractor_x,
                                                   &GroundTruth::distractor_y};

void put_truth_header(const GroundTruth& g, uint8_t* p) {
  put_le32(p, g.episode);
  p[4] = g.ball_grasped ? 1 : 0;
}

CodecStatus get_truth_header(const uint8_t* p, GroundTruth* g) {
  if ((p[4] & 0xFE) != 0) return CodecStatus::kOutOfRange;  // reserved flag bits
  g->episode = get_le32(p);
  g->ball_grasped = (p[4] & 1) != 0;
  return CodecStatus::kOk;
}

}  // namespace

CodecStatus angle_to_counts(double angle_rad, int32_t* counts) {
  if (std::isnan(angle_rad)) {
    *counts = 0;
    return CodecStatus::kOutOfRange;
  }
  const double r = std::round(angle_rad * kCountsPerRad);  // half away from zero
  if (r > 2147483647.0) {
    *counts = INT32_MAX;
    return CodecStatus::kOutOfRange;
  }
  if (r < -2147483648.0) {
    *counts = INT32_MIN;
    return CodecStatus::kOutOfRange;
  }
  *counts = static_cast<int32_t>(r);
  return CodecStatus::kOk;
}

uint8_t camera_pixel(double v) {
  if (!(v > 0.0)) return 0;  // also NaN
  if (v >= 1.0) return 255;
  return static_cast<uint8_t>(std::round(v * 255.0));
}

CanFrame encode_joint_command(const JointCommand& c) {
  return pdo(kCobRpdo1 + c.node, c.controlword, c.target_counts);
}

CodecStatus decode_joint_command(const CanFrame& f, JointCommand* out) {
  uint8_t node = 0;
  const CodecStatus s = check_joint_pdo(f, kCobRpdo1, &node);
  if (s != CodecStatus::kOk) return s;
  out->node = node;
  out->controlword = get_le16(f.data);
  out->target_counts = static_cast<int32_t>(get_le32(f.data + 2));
  return CodecStatus::kOk;
}

CanFrame encode_joint_feedback(const JointFeedback& fb) {
  return pdo(kCobTpdo1 + fb.node, fb.statusword, fb.actual_counts);
}

CodecStatus decode_joint_feedback(const CanFrame& f, JointFeedback* out) {
  uint8_t node = 0;
  const CodecStatus s = check_joint_pdo(f, kCobTpdo1, &node);
  if (s != CodecStatus::kOk) return s;
  out->node = node;
  out->statusword = get_le16(f.data);
  out->actual_counts = static_cast<int32_t>(get_le32(f.data + 2));
  return CodecStatus::kOk;
}

IsoTpLink camera_link_for_camera(CanProfile profile) {
  IsoTpLink l;
  l.tx_id = kCameraImageId;
  l.rx_id = kCameraFlowControlId;
  l.extended = true;
  l.fd = profile == CanProfile::kFd;
  l.tx_dl = l.fd ? 64 : 8;
  return l;
}

IsoTpLink camera_link_for_controller(CanProfile profile) {
  IsoTpLink l = camera_link_for_camera(profile);
  l.tx_id = kCameraFlowControlId;
  l.rx_id = kCameraImageId;
  // One burst of 195 CFs (FD) or 1,756 (classic), BS 0, STmin 0: the host backends buffer
  // it. A hardware port would ask for its RX FIFO depth as block size.
  l.block_size = 0;
  l.st_min = 0;
  return l;
}

CanFrame encode_camera_capture(const CameraCapture& c) {
  CanFrame f;
  f.id = kCobCameraCapture;
  f.len = kCameraCaptureBytes;
  put_le32(f.data, c.episode);
  return f;
}

CodecStatus decode_camera_capture(const CanFrame& f, CameraCapture* out) {
  const CodecStatus s = check_classic(f, kCobCameraCapture, kCameraCaptureBytes);
  if (s != CodecStatus::kOk) return s;
  out->episode = get_le32(f.data);
  return CodecStatus::kOk;
}

CanFrame encode_ground_truth(const GroundTruth& g) {
  CanFrame f;
  f.id = kCobGroundTruth;
  f.flags = hal::kFlagFd | hal::kFlagBrs;
  f.len = kGroundTruthBytes;
  put_truth_header(g, f.data);
  for (size_t i = 0; i < 4; ++i)
    put_le64(f.data + 8 + 8 * i, std::bit_cast<uint64_t>(g.*kTruthValues[i]));
  return f;
}

CodecStatus decode_ground_truth(const CanFrame& f, GroundTruth* out) {
  if (f.id != kCobGroundTruth) return CodecStatus::kWrongId;
  if (f.extended() || !f.fd() || f.error()) return CodecStatus::kBadFormat;
  if (f.len != kGroundTruthBytes) return CodecStatus::kBadLength;
  const CodecStatus s = get_truth_header(f.data, out);
  if (s != CodecStatus::kOk) return s;
  for (size_t i = 0; i < 4; ++i)
    out->*kTruthValues[i] = std::bit_cast<double>(get_le64(f.data + 8 + 8 * i));
  return CodecStatus::kOk;
}

size_t encode_ground_truth(const GroundTruth& g, CanProfile profile,
                           CanFrame out[kGroundTruthClassicFrames]) {
  if (profile == CanProfile::kFd) {
    out[0] = encode_ground_truth(g);
    return 1;
  }
  CanFrame& header = out[0];
  header = CanFrame{};
  header.id = kCobGroundTruthClassic;
  header.len = 8;
  put_truth_header(g, header.data);
  for (size_t i = 0; i < 4; ++i) {
    CanFrame& f = out[1 + i];
    f = CanFrame{};
    f.id = kCobGroundTruthClassic + 1 + static_cast<uint32_t>(i);
    f.len = 8;
    put_le64(f.data, std::bit_cast<uint64_t>(g.*kTruthValues[i]));
  }
  return kGroundTruthClassicFrames;
}

CodecStatus GroundTruthAssembler::on_frame(const CanFrame& f, GroundTruth* out, bool* complete) {
  *complete = false;
  if (f.id < kCobGroundTruth || f.id > kCobGroundTruthLast || f.extended())
    return CodecStatus::kWrongId;
  if (f.id == kCobGroundTruth) {  // the FD profile's single frame
    next_part_ = 0;
    const CodecStatus s = decode_ground_truth(f, out);
    *complete = s == CodecStatus::kOk;
    return s;
  }
  const size_t part = f.id - kCobGroundTruthClassic;
  CodecStatus s = check_classic(f, f.id, 8);
  if (s == CodecStatus::kOk && part == 0) {
    partial_ = GroundTruth{};
    s = get_truth_header(f.data, &partial_);
  } else if (s == CodecStatus::kOk && part != next_part_) {
    s = CodecStatus::kBadCommand;
  }
  if (s != CodecStatus::kOk) {
    next_part_ = 0;
    return s;
  }
  if (part == 0) {
    next_part_ = 1;
    return CodecStatus::kOk;
  }
  partial_.*kTruthValues[part - 1] = std::bit_cast<double>(get_le64(f.data));
  if (part + 1 < kGroundTruthClassicFrames) {
    next_part_ = part + 1;
    return CodecStatus::kOk;
  }
  next_part_ = 0;
  *out = partial_;
  *complete = true;
  return CodecStatus::kOk;
}

MessageKind classify(const CanFrame& f, uint8_t* node) {
  *node = 0;
  if (f.error()) return MessageKind::kUnknown;
  if (f.extended()) {
    if (f.id == kCameraImageId) return MessageKind::kCameraImage;
    if (f.id == kCameraFlowControlId) return MessageKind::kCameraFlowControl;
    return MessageKind::kUnknown;
  }
  if (f.id == kCobNmt) return MessageKind::kNmt;
  if (f.id == kCobSync) return MessageKind::kSync;
  if (f.id == kCobCameraCapture) {
    *node = kCameraNode;
    return MessageKind::kCameraCapture;
  }
  if (f.id >= kCobGroundTruth && f.id <= kCobGroundTruthLast) {
    *node = kCameraNode;
    return MessageKind::kGroundTruth;
  }
  const uint32_t function = f.id & 0x780;
  const auto n = static_cast<uint8_t>(f.id & 0x7F);
  if (n == 0) return MessageKind::kUnknown;
  *node = n;
  MessageKind kind = MessageKind::kUnknown;
  bool joint_only = false;
  switch (function) {
    case kCobEmcy:
      kind = MessageKind::kEmcy;
      break;
    case kCobTpdo1:
      kind = MessageKind::kJointFeedback;
      joint_only = true;
      break;
    case kCobRpdo1:
      kind = MessageKind::kJointCommand;
      joint_only = true;
      break;
    case kCobSdoResponse:
      kind = MessageKind::kSdoResponse;
      break;
    case kCobSdoRequest:
      kind = MessageKind::kSdoRequest;
      break;
    case kCobHeartbeat:
      kind = MessageKind::kHeartbeat;
      break;
    default:
      return MessageKind::kUnknown;
  }
  const bool ours = joint_only ? is_joint_node(n) : is_curio_node(n);
  return ours ? kind : MessageKind::kForeign;
}

}  // namespace curio::protocol
