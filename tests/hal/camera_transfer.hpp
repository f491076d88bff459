// A camera frame over a real bus: the camera node's ISO-TP sender on one endpoint, the
// controller's receiver on another, optionally a third endpoint flooding foreign frames.
// Shared by the in-process tests and the vcan tests run inside User-mode Linux.
#pragma once
#include <gtest/gtest.h>

#include <vector>

#include "hal/can_bus.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/isotp.hpp"

namespace curio::hal::test {

struct TransferResult {
  protocol::IsoTpStatus status = protocol::IsoTpStatus::kIdle;
  std::vector<uint8_t> image;
  uint64_t image_frames = 0;      // the camera's ISO-TP frames the controller received
  uint64_t foreign_seen = 0;      // flood frames the controller received
  uint64_t foreign_accepted = 0;  // flood frames any decoder accepted (must stay 0)
  protocol::IsoTpCounters rx_counters;
};

inline std::vector<uint8_t> test_image() {
  std::vector<uint8_t> img(protocol::kCameraImageBytes);
  for (size_t i = 0; i < img.size(); ++i) img[i] = protocol::camera_pixel(((i * 37) % 256) / 255.0);
  return img;
}

// A frame no Curio decoder may accept: near-miss ids of our messages, foreign nodes, other
// formats. Never exactly one of our ids with our format.
inline CanFrame foreign_frame(uint32_t k) {
  static const uint32_t near_misses[] = {0x208, 0x188, 0x221, 0x29F, 0x2A6, 0x708,
                                         0x608, 0x588, 0x0A1, 0x001, 0x7E5, 0x100};
  CanFrame f;
  const uint32_t pick = k % 5;
  if (pick == 0) {
    f.id = near_misses[(k / 5) % 12];
  } else if (pick == 1) {
    f.id = 0x18DAF121u - (k % 3) * 0x100u;  // other ISO-TP addresses
    f.flags = kFlagExtended;
  } else if (pick == 2) {
    f.id = 0x200 + protocol::kCameraNode + 1 + (k % 64);  // RPDO1 of foreign nodes
  } else if (pick == 3) {
    f.id = (k * 2654435761u) & kExtIdMask;
    f.flags = kFlagExtended;
    if (f.id == protocol::kCameraImageId || f.id == protocol::kCameraFlowControlId) f.id ^= 1;
  } else {
    f.id = 0x180 + 8 + (k % 100);  // TPDO1 of foreign nodes
  }
  const bool fd = (k & 1) != 0;
  if (fd) f.flags = static_cast<uint8_t>(f.flags | kFlagFd);
  f.len = fd ? dlc_to_len(static_cast<uint8_t>(k % 16)) : static_cast<uint8_t>(k % 9);
  for (size_t i = 0; i < f.len; ++i) f.data[i] = static_cast<uint8_t>(k * 7 + i);
  return f;
}

// True if any Curio decoder accepts `f` (flood frames must never be accepted).
inline bool any_decoder_accepts(const CanFrame& f) {
  using namespace protocol;
  NmtMessage nmt;
  uint8_t counter;
  Heartbeat hb;
  Emergency em;
  SdoMessage sdo;
  JointCommand jc;
  JointFeedback jf;
  CameraCapture cc;
  GroundTruth gt;
  GroundTruthAssembler assembler;  // a fresh one: a classic header would be accepted
  bool complete = false;
  return assembler.on_frame(f, &gt, &complete) == CodecStatus::kOk || decode_nmt(f, &nmt) == CodecStatus::kOk || decode_sync(f, &counter) == CodecStatus::kOk ||
         decode_heartbeat(f, &hb) == CodecStatus::kOk || decode_emcy(f, &em) == CodecStatus::kOk ||
         decode_sdo(f, &sdo) == CodecStatus::kOk ||
         decode_joint_command(f, &jc) == CodecStatus::kOk ||
         decode_joint_feedback(f, &jf) == CodecStatus::kOk ||
         decode_camera_capture(f, &cc) == CodecStatus::kOk ||
         decode_ground_truth(f, &gt) == CodecStatus::kOk;
}

// Runs one image transfer in the buses' profile (classic if either end is classic); `flood`
// (may be null) sends `flood_per_step` foreign frames per camera frame.
inline TransferResult transfer_image(CanBus& camera, CanBus& controller, CanBus* flood = nullptr,
                                     unsigned flood_per_step = 0) {
  using namespace protocol;
  TransferResult r;
  const auto image = test_image();
  const CanProfile profile = profile_for(camera.carries_fd() && controller.carries_fd());
  IsoTpSender tx(camera_link_for_camera(profile));
  r.image.assign(kIsoTpMaxMessage, 0);
  IsoTpReceiver rx(camera_link_for_controller(profile), r.image.data(), r.image.size());
  auto deadline = [](CanBus& b) { return b.now_us() + 1'000'000; };
  tx.start(image.data(), image.size(), camera.now_us());
  uint32_t k = 0;
  CanFrame batch[64];
  for (int idle = 0; idle < 2000;) {
    // Camera: FC frames in, data frames out.
    size_t n = 0;
    camera.receive_batch(batch, 64, &n);
    for (size_t i = 0; i < n; ++i) tx.on_frame(batch[i], camera.now_us());
    IsoTpReply out;
    const IsoTpStatus ts = tx.poll(camera.now_us(), &out);
    if (out.valid) {
      EXPECT_EQ(camera.send(out.frame, deadline(camera)), CanStatus::kOk);
    }
    if (ts != IsoTpStatus::kInProgress && ts != IsoTpStatus::kComplete &&
        ts != IsoTpStatus::kIdle) {
      r.status = ts;
      return r;
    }
    if (flood) {
      for (unsigned j = 0; j < flood_per_step; ++j)
        flood->send(foreign_frame(k++), deadline(*flood));
    }
    // Controller: everything in; image frames to ISO-TP, the rest to the decoders.
    const CanStatus rs = controller.receive_wait(batch, 64, &n, out.valid ? 0 : 2000);
    if (rs != CanStatus::kOk) n = 0;
    idle = n == 0 && !out.valid ? idle + 1 : 0;
    for (size_t i = 0; i < n; ++i) {
      uint8_t node = 0;
      if (classify(batch[i], &node) == MessageKind::kCameraImage) {
        ++r.image_frames;
        IsoTpReply fc;
        const IsoTpStatus s = rx.on_frame(batch[i], controller.now_us(), &fc);
        if (fc.valid) {
          EXPECT_EQ(controller.send(fc.frame, deadline(controller)), CanStatus::kOk);
        }
        if (s == IsoTpStatus::kComplete) {
          r.status = s;
          r.rx_counters = rx.counters();
          return r;
        }
        if (s != IsoTpStatus::kInProgress) {
          r.status = s;
          return r;
        }
      } else {
        ++r.foreign_seen;
        if (any_decoder_accepts(batch[i])) ++r.foreign_accepted;
      }
    }
  }
  r.status = IsoTpStatus::kTimeout;
  return r;
}

}  // namespace curio::hal::test
