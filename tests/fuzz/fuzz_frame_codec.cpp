// libFuzzer target: arbitrary frames (and raw bytes) through every frame-level decoder: the
// frame validity rules, the can-utils text and UDP datagram codecs, the CANopen/Curio
// decoders and the classifier. Oracles beyond "no crash, no UB": anything a decoder accepts
// re-encodes to the same bytes (or, for lossy forms, decodes again to the same message).
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "hal/host/can_text.hpp"
#include "hal/linux/udp_bus.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/canopen.hpp"

using namespace curio;
using namespace curio::protocol;

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

void check_same(const CanFrame& a, const CanFrame& b) {
  check(hal::same_frame(a, b));
}

void decoders(const CanFrame& f) {
  uint8_t node = 0;
  (void)classify(f, &node);
  NmtMessage nmt;
  if (decode_nmt(f, &nmt) == CodecStatus::kOk) check_same(encode_nmt(nmt), f);
  uint8_t counter = 0;
  if (decode_sync(f, &counter) == CodecStatus::kOk && f.len == 1)
    check_same(encode_sync(counter), f);
  Heartbeat hb;
  if (decode_heartbeat(f, &hb) == CodecStatus::kOk) {
    Heartbeat again;
    check(decode_heartbeat(encode_heartbeat(hb), &again) == CodecStatus::kOk);
    check(again.node == hb.node && again.state == hb.state);
  }
  Emergency em;
  if (decode_emcy(f, &em) == CodecStatus::kOk) check_same(encode_emcy(em), f);
  SdoMessage sdo;
  if (decode_sdo(f, &sdo) == CodecStatus::kOk) {
    SdoMessage again;
    check(decode_sdo(encode_sdo(sdo), &again) == CodecStatus::kOk);
    check(again.kind == sdo.kind && again.node == sdo.node && again.index == sdo.index &&
          again.subindex == sdo.subindex && again.value == sdo.value);
  }
  JointCommand jc;
  if (decode_joint_command(f, &jc) == CodecStatus::kOk) check_same(encode_joint_command(jc), f);
  JointFeedback jf;
  if (decode_joint_feedback(f, &jf) == CodecStatus::kOk) check_same(encode_joint_feedback(jf), f);
  CameraCapture cc;
  if (decode_camera_capture(f, &cc) == CodecStatus::kOk) check_same(encode_camera_capture(cc), f);
  GroundTruth gt;
  if (decode_ground_truth(f, &gt) == CodecStatus::kOk) {
    const CanFrame again = encode_ground_truth(gt);
    check(std::memcmp(again.data, f.data, 5) == 0 &&
          std::memcmp(again.data + 8, f.data + 8, 32) == 0);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  const int mode = in.ConsumeIntegralInRange(0, 3);
  if (mode == 0) {  // a structured frame; mostly valid, sometimes not
    CanFrame f;
    f.id = in.ConsumeBool() ? in.ConsumeIntegralInRange<uint32_t>(0, 0x7FF)
                            : in.ConsumeIntegral<uint32_t>();
    f.flags = in.ConsumeIntegral<uint8_t>();
    if (in.ConsumeBool()) f.flags &= hal::kFlagExtended | hal::kFlagFd | hal::kFlagRemote;
    f.len = in.ConsumeIntegralInRange<uint8_t>(0, 64);
    const auto bytes = in.ConsumeBytes<uint8_t>(f.len);
    if (!bytes.empty()) std::memcpy(f.data, bytes.data(), bytes.size());
    check(hal::len_to_dlc(f.len) <= 15 && hal::dlc_to_len(hal::len_to_dlc(f.len)) >= f.len);
    if (hal::is_valid(f) && !f.error()) {
      // Text and datagram codecs round-trip every valid frame.
      CanFrame back;
      const std::string text = hal::format_frame(f);
      check(hal::parse_frame(text, &back));
      if (!f.remote()) check_same(back, f);
      uint8_t dgram[hal::kUdpHeaderBytes + 64];
      const size_t n = hal::encode_udp_datagram(f, dgram);
      check(hal::decode_udp_datagram(dgram, n, &back));
      check_same(back, f);
      decoders(f);
    }
  } else if (mode == 1) {  // raw text
    const std::string text = in.ConsumeRemainingBytesAsString();
    CanFrame f;
    if (hal::parse_frame(text, &f)) {
      check(hal::is_valid(f));
      decoders(f);
    }
  } else {  // raw datagram
    const auto bytes = in.ConsumeRemainingBytes<uint8_t>();
    CanFrame f;
    if (hal::decode_udp_datagram(bytes.data(), bytes.size(), &f)) {
      check(hal::is_valid(f));
      decoders(f);
    }
  }
  return 0;
}
