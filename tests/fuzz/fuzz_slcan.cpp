// libFuzzer target: arbitrary bytes through the SLCAN line assembler (firmware/protocol/slcan)
// in both modes, and arbitrary frames through the encoder. Oracles beyond "no crash, no UB":
// every decoded frame is valid and re-encodes to a line that decodes to the same frame; every
// frame with an SLCAN form encodes to exactly slcan_line_length bytes and decodes back; the
// counters add up to the lines that ended.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdlib>

#include "firmware/protocol/slcan.hpp"

using namespace curio;
using namespace curio::protocol;

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

// Encode → decode must be the identity on frames that have a line.
void round_trip(const CanFrame& f, SlcanMode mode) {
  char line[kSlcanMaxLine];
  const size_t n = slcan_encode(f, mode, line, sizeof line);
  check(n == slcan_line_length(f, mode));
  if (n == 0) return;
  check(n <= kSlcanMaxLine && line[n - 1] == '\r');
  if (!f.fd()) check(n <= kSlcanMaxClassicLine);
  CanFrame back;
  check(slcan_decode(line, n - 1, mode, &back) == SlcanStatus::kFrame);
  check(hal::same_frame(f, back));
}

void stream(const uint8_t* data, size_t size, SlcanMode mode) {
  SlcanLineAssembler a(mode);
  uint32_t ended = 0;
  for (size_t i = 0; i < size; ++i) {
    CanFrame f;
    const SlcanStatus s = a.push(data[i], &f);
    if (s == SlcanStatus::kPending) continue;
    ++ended;
    if (s == SlcanStatus::kFrame) {
      check(hal::is_valid(f));
      check(mode == SlcanMode::kFd || !f.fd());
      round_trip(f, mode);
    }
  }
  const SlcanCounters& c = a.counters();
  check(c.frames + c.commands + c.malformed() == ended);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  stream(data, size, SlcanMode::kClassic);
  stream(data, size, SlcanMode::kFd);

  FuzzedDataProvider in(data, size);
  CanFrame f;
  f.id = in.ConsumeIntegral<uint32_t>() & (in.ConsumeBool() ? hal::kExtIdMask : 0x7FFu);
  f.flags = in.ConsumeIntegral<uint8_t>() & hal::kAllFlags;
  f.len = in.ConsumeIntegralInRange<uint8_t>(0, hal::kFdMaxLen);
  // A remote request carries a length but no data: its payload bytes stay zero.
  if (!f.remote())
    for (uint8_t i = 0; i < f.len; ++i) f.data[i] = in.ConsumeIntegral<uint8_t>();
  round_trip(f, SlcanMode::kClassic);
  round_trip(f, SlcanMode::kFd);
  return 0;
}
