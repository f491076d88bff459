// SLCAN framing (firmware/protocol/slcan): the lines of the kernel's slcan driver and slcand (the
// driver's own examples: t1232AABB ↔ 123#AABB, 321#DEADBEEF ↔ t3214DEADBEEF), the FD extension,
// every malformed-line class and the streaming assembler's fixed buffer.
#include <gtest/gtest.h>

#include <string>

#include "firmware/protocol/slcan.hpp"
#include "hal/can_frame.hpp"

using namespace curio::protocol;
using curio::hal::CanFrame;

namespace {

CanFrame frame(uint32_t id, std::initializer_list<uint8_t> bytes, uint8_t flags = 0) {
  CanFrame f;
  f.id = id;
  f.flags = flags;
  f.len = static_cast<uint8_t>(bytes.size());
  size_t i = 0;
  for (uint8_t b : bytes) f.data[i++] = b;
  return f;
}

std::string encode(const CanFrame& f, SlcanMode mode = SlcanMode::kClassic) {
  char buf[kSlcanMaxLine];
  const size_t n = slcan_encode(f, mode, buf, sizeof buf);
  EXPECT_EQ(n, slcan_line_length(f, mode));
  return std::string(buf, n);
}

SlcanStatus decode(const std::string& line, CanFrame* out, SlcanMode mode = SlcanMode::kClassic) {
  return slcan_decode(line.data(), line.size(), mode, out);
}

}  // namespace

TEST(Slcan, EncodesTheKernelDriversLines) {
  EXPECT_EQ(encode(frame(0x321, {0xDE, 0xAD, 0xBE, 0xEF})), "t3214DEADBEEF\r");
  EXPECT_EQ(encode(frame(0x123, {0xAA, 0xBB})), "t1232AABB\r");
  EXPECT_EQ(encode(frame(0x080, {})), "t0800\r");
  EXPECT_EQ(encode(frame(0x18DAF120, {1, 2, 3}, curio::hal::kFlagExtended)), "T18DAF1203010203\r");
  CanFrame rtr = frame(0x7FF, {}, curio::hal::kFlagRemote);
  rtr.len = 4;
  EXPECT_EQ(encode(rtr), "r7FF4\r");
  rtr.flags |= curio::hal::kFlagExtended;
  rtr.id = 0x1FFFFFFF;
  EXPECT_EQ(encode(rtr), "R1FFFFFFF4\r");
}

TEST(Slcan, DecodesWhatItEncodesForEveryClassicLengthAndIdWidth) {
  for (uint8_t len = 0; len <= 8; ++len) {
    for (uint8_t flags : {uint8_t{0}, curio::hal::kFlagExtended, curio::hal::kFlagRemote,
                          uint8_t(curio::hal::kFlagExtended | curio::hal::kFlagRemote)}) {
      CanFrame f;
      f.id = (flags & curio::hal::kFlagExtended) ? 0x1ABCDEF5u : 0x5A5u;
      f.flags = flags;
      f.len = len;
      if (!f.remote())
        for (uint8_t i = 0; i < len; ++i) f.data[i] = static_cast<uint8_t>(0x11 * i + 0x0F);
      const std::string line = encode(f);
      ASSERT_FALSE(line.empty());
      CanFrame back;
      ASSERT_EQ(decode(line.substr(0, line.size() - 1), &back), SlcanStatus::kFrame) << line;
      EXPECT_TRUE(curio::hal::same_frame(f, back)) << line;
    }
  }
}

TEST(Slcan, FdLinesOnlyInFdMode) {
  uint8_t payload[64];
  for (int i = 0; i < 64; ++i) payload[i] = static_cast<uint8_t>(i);
  for (size_t len : {0, 8, 12, 48, 64}) {
    CanFrame f;
    ASSERT_TRUE(curio::hal::make_frame(&f, 0x18DAF120, true, true, payload, len));  // FD + BRS
    EXPECT_EQ(slcan_line_length(f, SlcanMode::kClassic), 0u) << "the kernel's slcan has no FD";
    const std::string line = encode(f, SlcanMode::kFd);
    ASSERT_EQ(line[0], 'B');
    EXPECT_EQ(line[9], "0123456789ABCDEF"[f.dlc()]);
    EXPECT_EQ(line.size(), 1 + 8 + 1 + 2 * len + 1);
    CanFrame back;
    ASSERT_EQ(decode(line.substr(0, line.size() - 1), &back, SlcanMode::kFd), SlcanStatus::kFrame);
    EXPECT_TRUE(curio::hal::same_frame(f, back));
    EXPECT_EQ(decode(line.substr(0, line.size() - 1), &back), SlcanStatus::kUnsupported);
  }
  CanFrame no_brs = frame(0x2A0, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, curio::hal::kFlagFd);
  EXPECT_EQ(encode(no_brs, SlcanMode::kFd), "d2A090102030405060708090A0B0C\r");
  CanFrame esi = no_brs;
  esi.flags |= curio::hal::kFlagEsi;
  EXPECT_EQ(slcan_line_length(esi, SlcanMode::kFd), 0u) << "ESI has no SLCAN form";
}

TEST(Slcan, RefusesFramesWithoutAnSlcanForm) {
  CanFrame err = frame(0x004, {0, 0, 0, 0, 0, 0, 0, 0}, curio::hal::kFlagError);
  EXPECT_EQ(slcan_line_length(err, SlcanMode::kFd), 0u);
  CanFrame bad = frame(0x800, {});  // 12-bit id in an 11-bit frame
  EXPECT_EQ(slcan_line_length(bad, SlcanMode::kFd), 0u);
  char small[4];
  EXPECT_EQ(slcan_encode(frame(0x123, {1}), SlcanMode::kClassic, small, sizeof small), 0u);
}

TEST(Slcan, AcceptsLowerCaseHexAndALawicelTimestamp) {
  CanFrame f;
  ASSERT_EQ(decode("t1a22aabb", &f), SlcanStatus::kFrame);
  EXPECT_EQ(f.id, 0x1A2u);
  EXPECT_EQ(f.len, 2);
  EXPECT_EQ(f.data[0], 0xAA);
  ASSERT_EQ(decode("t1232AABB1F3C", &f), SlcanStatus::kFrame) << "Z1 timestamp";
  EXPECT_EQ(f.len, 2);
  EXPECT_EQ(decode("t1232AABB1F3G", &f), SlcanStatus::kBadHex);
}

TEST(Slcan, NamesEachKindOfMalformedLine) {
  CanFrame f = frame(0x55, {0x55});
  const CanFrame before = f;
  EXPECT_EQ(decode("t12", &f), SlcanStatus::kBadId);
  EXPECT_EQ(decode("t1G30", &f), SlcanStatus::kBadId);
  EXPECT_EQ(decode("t8000", &f), SlcanStatus::kBadId) << "0x800 > 11 bits";
  EXPECT_EQ(decode("T200000000", &f), SlcanStatus::kBadId) << "> 29 bits";
  EXPECT_EQ(decode("t123", &f), SlcanStatus::kBadLength) << "no length digit";
  EXPECT_EQ(decode("t1239", &f), SlcanStatus::kBadLength) << "classic length > 8";
  EXPECT_EQ(decode("t1232AA", &f), SlcanStatus::kBadLength) << "fewer bytes than the length";
  EXPECT_EQ(decode("t1231AABB", &f), SlcanStatus::kBadLength) << "more bytes than the length";
  EXPECT_EQ(decode("t123XAA", &f), SlcanStatus::kBadLength);
  EXPECT_EQ(decode("t1232AXBB", &f), SlcanStatus::kBadHex);
  EXPECT_EQ(decode("r1232AABBCC", &f), SlcanStatus::kBadLength) << "remote lines carry no data";
  EXPECT_EQ(decode("d1239AABB", &f, SlcanMode::kFd), SlcanStatus::kBadLength) << "DLC 9 = 12 B";
  EXPECT_TRUE(curio::hal::same_frame(f, before)) << "a malformed line leaves the frame alone";
  EXPECT_EQ(decode("O", &f), SlcanStatus::kCommand);
  EXPECT_EQ(decode("S6", &f), SlcanStatus::kCommand);
  EXPECT_EQ(decode("", &f), SlcanStatus::kCommand);
}

TEST(SlcanLineAssembler, SplitsAStreamIntoFramesAndCountsTheRest) {
  // slcand's set-up, two frames, CR LF line ends, a bad line, an adapter error bell.
  const std::string stream = "C\rS6\rO\rt1232AABB\r\nT18DAF1201FF\rt12\r\a\r";
  SlcanLineAssembler a;
  std::vector<CanFrame> frames;
  std::vector<SlcanStatus> ends;
  for (char c : stream) {
    CanFrame f;
    const SlcanStatus s = a.push(static_cast<uint8_t>(c), &f);
    if (s == SlcanStatus::kFrame) frames.push_back(f);
    if (s != SlcanStatus::kPending) ends.push_back(s);
  }
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].id, 0x123u);
  EXPECT_EQ(frames[1].id, 0x18DAF120u);
  EXPECT_TRUE(frames[1].extended());
  const SlcanCounters& c = a.counters();
  EXPECT_EQ(c.frames, 2u);
  EXPECT_EQ(c.commands, 4u) << "C, S6, O and the bell";
  EXPECT_EQ(c.bad_id, 1u);
  EXPECT_EQ(c.malformed(), 1u);
  EXPECT_EQ(ends.size(), 7u);
}

TEST(SlcanLineAssembler, DiscardsAnOverlongLineOnceAndRecovers) {
  SlcanLineAssembler a(SlcanMode::kFd);
  CanFrame f;
  int overlong = 0;
  for (size_t i = 0; i < 3 * kSlcanMaxLine; ++i)
    if (a.push('A', &f) == SlcanStatus::kOverlong) ++overlong;
  EXPECT_EQ(overlong, 1);
  EXPECT_EQ(a.push('\r', &f), SlcanStatus::kPending) << "the end of the dropped line";
  // The longest legal line still fits the buffer.
  uint8_t payload[64] = {};
  CanFrame big;
  ASSERT_TRUE(curio::hal::make_frame(&big, 0x1FFFFFFF, true, true, payload, 64));
  char line[kSlcanMaxLine];
  const size_t n = slcan_encode(big, SlcanMode::kFd, line, sizeof line);
  ASSERT_EQ(n, kSlcanMaxLine);
  SlcanStatus last = SlcanStatus::kPending;
  for (size_t i = 0; i < n; ++i) last = a.push(static_cast<uint8_t>(line[i]), &f);
  EXPECT_EQ(last, SlcanStatus::kFrame);
  EXPECT_TRUE(curio::hal::same_frame(f, big));
  EXPECT_EQ(a.counters().overlong, 1u);
}

TEST(SlcanLineAssembler, ClassicModeCountsFdLinesAsUnsupported) {
  SlcanLineAssembler a;
  CanFrame f;
  SlcanStatus last = SlcanStatus::kPending;
  for (char c : std::string("d1230\r")) last = a.push(static_cast<uint8_t>(c), &f);
  EXPECT_EQ(last, SlcanStatus::kUnsupported);
  EXPECT_EQ(a.counters().unsupported, 1u);
}
