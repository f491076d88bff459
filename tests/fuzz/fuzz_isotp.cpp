// libFuzzer target: ISO-TP reassembly and flow-control handling from arbitrary frame
// sequences and times. Oracles beyond "no crash, no UB": the receiver never reports more
// bytes than its buffer holds; a message sent by our sender through arbitrary interleaved
// junk (other ids) and arbitrary time steps within the timeouts arrives intact.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/isotp.hpp"

using namespace curio;
using namespace curio::protocol;

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

CanFrame fuzzed_frame(FuzzedDataProvider& in, uint32_t our_id) {
  CanFrame f;
  f.id = in.ConsumeBool() ? our_id : in.ConsumeIntegralInRange<uint32_t>(0, hal::kExtIdMask);
  f.flags =
      static_cast<uint8_t>(in.ConsumeIntegral<uint8_t>() & (hal::kFlagExtended | hal::kFlagFd));
  if (f.id == our_id) f.flags |= hal::kFlagExtended;
  const bool fd = f.fd();
  f.len = fd ? hal::dlc_to_len(in.ConsumeIntegralInRange<uint8_t>(0, 15))
             : in.ConsumeIntegralInRange<uint8_t>(0, 8);
  const auto bytes = in.ConsumeBytes<uint8_t>(f.len);
  if (!bytes.empty()) std::memcpy(f.data, bytes.data(), bytes.size());
  // Bias towards well-formed PCIs so the fuzzer reaches deep states quickly.
  if (f.len > 0 && in.ConsumeBool()) {
    f.data[0] =
        static_cast<uint8_t>((in.ConsumeIntegralInRange<uint8_t>(0, 3) << 4) | (f.data[0] & 0x0F));
  }
  return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  const size_t capacity =
      in.ConsumeBool() ? kIsoTpMaxMessage : in.ConsumeIntegralInRange<size_t>(0, 300);
  std::vector<uint8_t> buffer(capacity);
  IsoTpLink rx_link = camera_link_for_controller(CanProfile::kFd);
  rx_link.block_size = in.ConsumeIntegral<uint8_t>();
  rx_link.st_min = in.ConsumeIntegral<uint8_t>();
  rx_link.fd = in.ConsumeBool();
  const int mode = in.ConsumeIntegralInRange(0, 2);

  if (mode == 0) {  // the receiver against arbitrary frames
    IsoTpReceiver rx(rx_link, buffer.data(), buffer.size());
    uint64_t now = 0;
    while (in.remaining_bytes() > 0) {
      now += in.ConsumeIntegralInRange<uint64_t>(0, 2'000'000);
      rx.hold(in.ConsumeBool() && in.ConsumeBool());
      IsoTpReply reply;
      IsoTpStatus s = in.ConsumeBool() ? rx.poll(now, &reply)
                                       : rx.on_frame(fuzzed_frame(in, kCameraImageId), now, &reply);
      if (s == IsoTpStatus::kComplete) check(rx.size() <= capacity);
      if (reply.valid) check(hal::is_valid(reply.frame) && reply.frame.id == rx_link.tx_id);
    }
  } else if (mode == 1) {  // the sender against arbitrary flow control
    const auto msg = in.ConsumeBytes<uint8_t>(in.ConsumeIntegralInRange<size_t>(1, 5000));
    if (msg.empty()) return 0;
    IsoTpLink tx_link = camera_link_for_camera(CanProfile::kFd);
    tx_link.tx_dl = hal::dlc_to_len(in.ConsumeIntegralInRange<uint8_t>(8, 15));
    IsoTpSender tx(tx_link);
    uint64_t now = 0;
    tx.start(msg.data(), msg.size(), now);
    size_t payload = 0;
    while (in.remaining_bytes() > 0 && tx.busy()) {
      now += in.ConsumeIntegralInRange<uint64_t>(0, 300'000);
      if (in.ConsumeBool()) {
        tx.on_frame(fuzzed_frame(in, kCameraFlowControlId), now);
      } else {
        IsoTpReply out;
        tx.poll(now, &out);
        if (out.valid) {
          check(hal::is_valid(out.frame) && out.frame.len >= 8);
          payload += out.frame.len;
        }
      }
    }
    check(payload <= 2 * msg.size() + 64 * 2);  // never sends past the message
  } else {  // round trip through junk and jittered time: must arrive intact
    const auto msg =
        in.ConsumeBytes<uint8_t>(in.ConsumeIntegralInRange<size_t>(1, kIsoTpMaxMessage));
    if (msg.empty() || msg.size() > capacity) return 0;
    IsoTpLink tx_link = camera_link_for_camera(CanProfile::kFd);
    tx_link.fd = rx_link.fd;
    tx_link.tx_dl = rx_link.fd ? hal::dlc_to_len(in.ConsumeIntegralInRange<uint8_t>(8, 15)) : 8;
    IsoTpSender tx(tx_link);
    IsoTpReceiver rx(rx_link, buffer.data(), buffer.size());
    uint64_t now = 0;
    tx.start(msg.data(), msg.size(), now);
    IsoTpStatus rs = IsoTpStatus::kIdle;
    for (int guard = 0; guard < 100000 && rs != IsoTpStatus::kComplete; ++guard) {
      now = std::max(now + in.ConsumeIntegralInRange<uint64_t>(0, 50'000), tx.next_event_us());
      if (in.remaining_bytes() > 0 && in.ConsumeIntegralInRange(0, 7) == 0) {
        CanFrame junk = fuzzed_frame(in, 0x123);
        if (junk.id == kCameraImageId || junk.id == kCameraFlowControlId) junk.id ^= 1;
        IsoTpReply ignored;
        check(rx.on_frame(junk, now, &ignored) == IsoTpStatus::kIgnored || !junk.extended() ||
              junk.id != kCameraImageId);
        check(tx.on_frame(junk, now) == IsoTpStatus::kIgnored || junk.id == kCameraFlowControlId);
      }
      IsoTpReply out;
      const IsoTpStatus ts = tx.poll(now, &out);
      check(ts == IsoTpStatus::kInProgress || ts == IsoTpStatus::kComplete ||
            ts == IsoTpStatus::kIdle);
      if (!out.valid) continue;
      IsoTpReply fc;
      rs = rx.on_frame(out.frame, now, &fc);
      check(rs == IsoTpStatus::kInProgress || rs == IsoTpStatus::kComplete);
      if (fc.valid) check(tx.on_frame(fc.frame, now) == IsoTpStatus::kInProgress);
    }
    check(rs == IsoTpStatus::kComplete);
    check(rx.size() == msg.size() && std::memcmp(rx.data(), msg.data(), msg.size()) == 0);
  }
  return 0;
}
