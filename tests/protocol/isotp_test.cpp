// ISO-TP: segmentation and reassembly (every size edge, FD and classic), flow control (block
// size, STmin, WAIT, overflow) and every fault the receiver and sender report.
#include <gtest/gtest.h>

#include <deque>
#include <vector>

#include "firmware/protocol/isotp.hpp"

using namespace curio::protocol;
using curio::hal::CanFrame;

namespace {

IsoTpLink link_a(bool fd = true) {  // sender side
  IsoTpLink l;
  l.tx_id = 0x700;
  l.rx_id = 0x701;
  l.fd = fd;
  l.tx_dl = fd ? 64 : 8;
  return l;
}
IsoTpLink link_b(bool fd = true) {  // receiver side
  IsoTpLink l = link_a(fd);
  std::swap(l.tx_id, l.rx_id);
  return l;
}

std::vector<uint8_t> pattern(size_t n) {
  std::vector<uint8_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = static_cast<uint8_t>(i * 31 + (i >> 8) + 7);
  return v;
}

// Moves frames between a sender and a receiver with a manual clock until done or stuck.
struct Transfer {
  IsoTpSender tx;
  IsoTpReceiver rx;
  std::vector<CanFrame> data_frames;  // sender → receiver
  std::vector<CanFrame> fc_frames;    // receiver → sender
  uint64_t now = 1000;
  IsoTpStatus rx_status = IsoTpStatus::kIdle;
  IsoTpStatus tx_status = IsoTpStatus::kIdle;

  Transfer(const IsoTpLink& a, const IsoTpLink& b, uint8_t* buf, size_t cap)
      : tx(a), rx(b, buf, cap) {}

  // Runs until the receiver completes or fails, or `max_steps` pass.
  void run(const uint8_t* data, size_t size, int max_steps = 100000) {
    tx_status = tx.start(data, size, now);
    for (int step = 0; step < max_steps; ++step) {
      IsoTpReply out;
      tx_status = tx.poll(now, &out);
      if (out.valid) {
        data_frames.push_back(out.frame);
        IsoTpReply fc;
        rx_status = rx.on_frame(out.frame, now, &fc);
        if (fc.valid) {
          fc_frames.push_back(fc.frame);
          tx_status = tx.on_frame(fc.frame, now);
        }
        if (rx_status != IsoTpStatus::kInProgress) return;
      } else if (!tx.busy()) {
        return;
      } else {
        now = std::max(now + 1, tx.next_event_us());
      }
    }
  }
};

}  // namespace

TEST(IsoTp, RoundTripsEverySizeEdgeOverFd) {
  for (size_t size : {1, 7, 8, 20, 62, 63, 64, 125, 4095, 4096, 5000, 12288}) {
    const auto msg = pattern(size);
    std::vector<uint8_t> buf(kIsoTpMaxMessage);
    Transfer t(link_a(), link_b(), buf.data(), buf.size());
    t.run(msg.data(), msg.size());
    ASSERT_EQ(t.rx_status, IsoTpStatus::kComplete) << "size " << size;
    EXPECT_EQ(t.tx_status, IsoTpStatus::kComplete);
    ASSERT_EQ(t.rx.size(), size);
    EXPECT_TRUE(std::equal(msg.begin(), msg.end(), t.rx.data())) << "size " << size;
    for (const auto& f : t.data_frames) {
      EXPECT_TRUE(f.fd());
      EXPECT_GE(f.len, 8);
    }
    const bool single = size <= 62;
    EXPECT_EQ(t.fc_frames.size(), single ? 0u : 1u) << "BS 0: one FC after the FF";
  }
}

TEST(IsoTp, RoundTripsOverClassicCan) {
  for (size_t size : {1, 7, 8, 100, 4095, 4096}) {
    const auto msg = pattern(size);
    std::vector<uint8_t> buf(8192);
    Transfer t(link_a(false), link_b(false), buf.data(), buf.size());
    t.run(msg.data(), msg.size());
    ASSERT_EQ(t.rx_status, IsoTpStatus::kComplete) << "size " << size;
    EXPECT_TRUE(std::equal(msg.begin(), msg.end(), t.rx.data()));
    for (const auto& f : t.data_frames) {
      EXPECT_FALSE(f.fd());
      EXPECT_EQ(f.len, 8) << "classic frames are padded to 8";
    }
  }
}

// Over a classic-only link (TX_DL 8) the camera frame takes 2 bytes in the escape FF and 7 per
// CF: 1 + ⌈12286 / 7⌉ = 1,757 frames instead of 196 (docs/can.md, "SLCAN").
TEST(IsoTp, CameraFrameOverClassicCanTakes1757Frames) {
  const auto msg = pattern(kIsoTpMaxMessage);
  std::vector<uint8_t> buf(kIsoTpMaxMessage);
  Transfer t(link_a(false), link_b(false), buf.data(), buf.size());
  t.run(msg.data(), msg.size());
  ASSERT_EQ(t.rx_status, IsoTpStatus::kComplete);
  EXPECT_TRUE(std::equal(msg.begin(), msg.end(), t.rx.data()));
  EXPECT_EQ(t.data_frames.size(), 1757u);
  for (const auto& f : t.data_frames) EXPECT_EQ(f.len, 8);
}

TEST(IsoTp, CameraFrameUsesTheEscapeFirstFrameAnd195ConsecutiveFrames) {
  const auto msg = pattern(12288);
  std::vector<uint8_t> buf(kIsoTpMaxMessage);
  Transfer t(link_a(), link_b(), buf.data(), buf.size());
  t.run(msg.data(), msg.size());
  ASSERT_EQ(t.rx_status, IsoTpStatus::kComplete);
  ASSERT_EQ(t.data_frames.size(), 196u);  // 58 bytes in the FF, then ⌈12230 / 63⌉ = 195 CFs
  const CanFrame& ff = t.data_frames[0];
  const uint8_t pci[6] = {0x10, 0x00, 0x00, 0x00, 0x30, 0x00};  // 12288 = 0x3000
  EXPECT_TRUE(std::equal(pci, pci + 6, ff.data));
  EXPECT_EQ(t.data_frames[1].data[0], 0x21);
  EXPECT_EQ(t.data_frames[15].data[0], 0x2F);
  EXPECT_EQ(t.data_frames[16].data[0], 0x20) << "sequence number wraps 15 → 0";
  const CanFrame& last = t.data_frames.back();
  EXPECT_EQ(last.len, 12) << "12230 - 194*63 = 8 bytes + PCI, padded to 12";
  EXPECT_EQ(last.data[9], 0xCC);
  EXPECT_EQ(t.rx.counters().completed, 1u);
}

TEST(IsoTp, ShortFormsAreEncodedAsTheStandardSays) {
  uint8_t buf[64];
  const auto msg = pattern(4095);
  IsoTpSender tx(link_a());
  IsoTpReply out;
  ASSERT_EQ(tx.start(msg.data(), 20, 0), IsoTpStatus::kInProgress);
  ASSERT_EQ(tx.poll(0, &out), IsoTpStatus::kComplete);
  EXPECT_EQ(out.frame.data[0], 0x00) << "FD escape single frame";
  EXPECT_EQ(out.frame.data[1], 20);
  EXPECT_EQ(out.frame.len, 24);
  EXPECT_EQ(out.frame.data[22], 0xCC);
  ASSERT_EQ(tx.start(msg.data(), 5, 0), IsoTpStatus::kInProgress);
  ASSERT_EQ(tx.poll(0, &out), IsoTpStatus::kComplete);
  EXPECT_EQ(out.frame.data[0], 0x05);
  EXPECT_EQ(out.frame.len, 8);
  ASSERT_EQ(tx.start(msg.data(), 4095, 0), IsoTpStatus::kInProgress);
  ASSERT_EQ(tx.poll(0, &out), IsoTpStatus::kInProgress);
  EXPECT_EQ(out.frame.data[0], 0x1F);
  EXPECT_EQ(out.frame.data[1], 0xFF);
  (void)buf;
}

TEST(IsoTp, BlockSizeAndStMinPaceTheSender) {
  IsoTpLink b = link_b();
  b.block_size = 4;
  b.st_min = 0xF5;                 // 500 µs
  const auto msg = pattern(1000);  // FF + 15 CFs
  std::vector<uint8_t> buf(1000);
  Transfer t(link_a(), b, buf.data(), buf.size());
  t.run(msg.data(), msg.size());
  ASSERT_EQ(t.rx_status, IsoTpStatus::kComplete);
  EXPECT_TRUE(std::equal(msg.begin(), msg.end(), t.rx.data()));
  EXPECT_EQ(t.fc_frames.size(), 4u) << "after the FF and after CF 4, 8, 12";
  EXPECT_EQ(t.fc_frames[1].data[1], 4);
  EXPECT_EQ(t.fc_frames[1].data[2], 0xF5);

  // STmin: the second CF of a block is not released before 500 µs.
  IsoTpSender tx(link_a());
  IsoTpReply out;
  tx.start(msg.data(), msg.size(), 0);
  tx.poll(0, &out);  // FF
  CanFrame fc = t.fc_frames[0];
  fc.id = link_a().rx_id;
  ASSERT_EQ(tx.on_frame(fc, 10), IsoTpStatus::kInProgress);
  ASSERT_EQ(tx.poll(10, &out), IsoTpStatus::kInProgress);
  EXPECT_TRUE(out.valid) << "first CF right after CTS";
  tx.poll(509, &out);
  EXPECT_FALSE(out.valid) << "STmin not yet over";
  EXPECT_EQ(tx.next_event_us(), 510u);
  tx.poll(510, &out);
  EXPECT_TRUE(out.valid);
}

TEST(IsoTp, OutOfOrderConsecutiveFrameDropsTheMessage) {
  const auto msg = pattern(300);
  std::vector<uint8_t> buf(300);
  IsoTpSender tx(link_a());
  IsoTpReceiver rx(link_b(), buf.data(), buf.size());
  IsoTpReply out, fc;
  tx.start(msg.data(), msg.size(), 0);
  tx.poll(0, &out);
  rx.on_frame(out.frame, 0, &fc);
  tx.on_frame(fc.frame, 0);
  tx.poll(0, &out);  // CF 1
  tx.poll(0, &out);  // CF 2: skip CF 1
  EXPECT_EQ(rx.on_frame(out.frame, 0, &fc), IsoTpStatus::kSequenceError);
  EXPECT_EQ(rx.counters().sequence_errors, 1u);
  EXPECT_FALSE(rx.busy());
  tx.poll(0, &out);
  EXPECT_EQ(rx.on_frame(out.frame, 0, &fc), IsoTpStatus::kUnexpected)
      << "rest of the dropped message";
}

TEST(IsoTp, TruncatedFramesAreRejected) {
  uint8_t buf[300];
  IsoTpReceiver rx(link_b(), buf, sizeof(buf));
  IsoTpReply fc;
  CanFrame f;
  f.id = link_b().rx_id;
  f.flags = curio::hal::kFlagFd;
  // SF announcing 7 bytes in a 4-byte frame.
  f.len = 4;
  f.data[0] = 0x07;
  EXPECT_EQ(rx.on_frame(f, 0, &fc), IsoTpStatus::kTruncated);
  // Escape SF announcing 40 bytes in a 32-byte frame.
  f.len = 32;
  f.data[0] = 0x00;
  f.data[1] = 40;
  EXPECT_EQ(rx.on_frame(f, 0, &fc), IsoTpStatus::kTruncated);
  // FF in a frame shorter than 8 bytes.
  f.len = 6;
  f.data[0] = 0x10;
  f.data[1] = 200;
  EXPECT_EQ(rx.on_frame(f, 0, &fc), IsoTpStatus::kTruncated);
  // A middle CF shorter than the FF's frame length.
  f.len = 64;
  f.data[1] = 200;
  ASSERT_EQ(rx.on_frame(f, 0, &fc), IsoTpStatus::kInProgress);
  CanFrame cf;
  cf.id = f.id;
  cf.flags = f.flags;
  cf.len = 32;
  cf.data[0] = 0x21;
  EXPECT_EQ(rx.on_frame(cf, 0, &fc), IsoTpStatus::kTruncated);
  // The last CF carrying fewer bytes than remain.
  ASSERT_EQ(rx.on_frame(f, 0, &fc), IsoTpStatus::kInProgress);  // 62 of 200
  cf.len = 64;
  ASSERT_EQ(rx.on_frame(cf, 0, &fc), IsoTpStatus::kInProgress);  // 125
  cf.data[0] = 0x22;
  ASSERT_EQ(rx.on_frame(cf, 0, &fc), IsoTpStatus::kInProgress);  // 188: 12 remain
  cf.data[0] = 0x23;
  cf.len = 12;  // 11 data bytes
  EXPECT_EQ(rx.on_frame(cf, 0, &fc), IsoTpStatus::kTruncated);
  EXPECT_EQ(rx.counters().truncated, 5u);
  // A flow control shorter than 3 bytes at the sender.
  IsoTpSender tx(link_a());
  IsoTpReply out;
  const auto msg = pattern(100);
  tx.start(msg.data(), msg.size(), 0);
  tx.poll(0, &out);
  CanFrame short_fc;
  short_fc.id = link_a().rx_id;
  short_fc.len = 2;
  short_fc.data[0] = 0x30;
  EXPECT_EQ(tx.on_frame(short_fc, 0), IsoTpStatus::kTruncated);
}

TEST(IsoTp, OversizedMessagesGetOverflowAndTheSenderAborts) {
  const auto msg = pattern(12289);
  std::vector<uint8_t> buf(kIsoTpMaxMessage);
  Transfer t(link_a(), link_b(), buf.data(), buf.size());
  t.run(msg.data(), msg.size());
  EXPECT_EQ(t.rx_status, IsoTpStatus::kOversized);
  ASSERT_EQ(t.fc_frames.size(), 1u);
  EXPECT_EQ(t.fc_frames[0].data[0], 0x32) << "flow status overflow";
  EXPECT_EQ(t.tx_status, IsoTpStatus::kOverflowAbort);
  EXPECT_EQ(t.tx.counters().overflow_aborts, 1u);
  EXPECT_EQ(t.rx.counters().oversized, 1u);
  // A single frame larger than a tiny buffer.
  uint8_t tiny[4];
  IsoTpReceiver rx(link_b(), tiny, sizeof(tiny));
  CanFrame sf;
  sf.id = link_b().rx_id;
  sf.len = 8;
  sf.data[0] = 0x07;
  IsoTpReply fc;
  EXPECT_EQ(rx.on_frame(sf, 0, &fc), IsoTpStatus::kOversized);
  EXPECT_FALSE(fc.valid) << "single frames get no flow control";
}

TEST(IsoTp, TimeoutsWhenThePeerFallsSilent) {
  const auto msg = pattern(500);
  std::vector<uint8_t> buf(500);
  IsoTpSender tx(link_a());
  IsoTpReceiver rx(link_b(), buf.data(), buf.size());
  IsoTpReply out, fc;
  tx.start(msg.data(), msg.size(), 0);
  tx.poll(0, &out);
  ASSERT_EQ(rx.on_frame(out.frame, 0, &fc), IsoTpStatus::kInProgress);
  // Receiver (N_Cr): no CF within 1 s.
  EXPECT_EQ(rx.poll(1'000'000, nullptr), IsoTpStatus::kInProgress);
  EXPECT_EQ(rx.poll(1'000'001, nullptr), IsoTpStatus::kTimeout);
  EXPECT_EQ(rx.counters().timeouts, 1u);
  EXPECT_FALSE(rx.busy());
  // Sender (N_Bs): the FC never came.
  EXPECT_EQ(tx.poll(1'000'000, &out), IsoTpStatus::kInProgress);
  EXPECT_EQ(tx.poll(1'000'001, &out), IsoTpStatus::kTimeout);
  EXPECT_EQ(tx.counters().timeouts, 1u);
  EXPECT_FALSE(tx.busy());
}

TEST(IsoTp, UnexpectedFramesAreCountedAndANewMessageWins) {
  const auto msg = pattern(300);
  std::vector<uint8_t> buf(300);
  IsoTpReceiver rx(link_b(), buf.data(), buf.size());
  IsoTpReply fc;
  CanFrame cf;
  cf.id = link_b().rx_id;
  cf.len = 8;
  cf.data[0] = 0x21;
  EXPECT_EQ(rx.on_frame(cf, 0, &fc), IsoTpStatus::kUnexpected) << "CF while idle";
  CanFrame flow = cf;
  flow.data[0] = 0x30;
  EXPECT_EQ(rx.on_frame(flow, 0, &fc), IsoTpStatus::kUnexpected) << "FC at a receiver";
  CanFrame junk = cf;
  junk.data[0] = 0x45;
  EXPECT_EQ(rx.on_frame(junk, 0, &fc), IsoTpStatus::kUnexpected) << "reserved PCI type";
  CanFrame other = cf;
  other.id = 0x123;
  EXPECT_EQ(rx.on_frame(other, 0, &fc), IsoTpStatus::kIgnored);
  EXPECT_EQ(rx.counters().ignored, 1u);

  // A first frame in the middle of a message: the old one is dropped, the new one completes.
  IsoTpSender tx1(link_a()), tx2(link_a());
  IsoTpReply out;
  tx1.start(msg.data(), 300, 0);
  tx1.poll(0, &out);
  rx.on_frame(out.frame, 0, &fc);
  const auto msg2 = pattern(200);
  tx2.start(msg2.data(), 200, 0);
  tx2.poll(0, &out);
  EXPECT_EQ(rx.on_frame(out.frame, 0, &fc), IsoTpStatus::kInProgress);
  tx2.on_frame(fc.frame, 0);
  IsoTpStatus s = IsoTpStatus::kInProgress;
  while (s == IsoTpStatus::kInProgress) {
    tx2.poll(0, &out);
    s = rx.on_frame(out.frame, 0, &fc);
  }
  EXPECT_EQ(s, IsoTpStatus::kComplete);
  EXPECT_EQ(rx.size(), 200u);
  EXPECT_TRUE(std::equal(msg2.begin(), msg2.end(), rx.data()));
  EXPECT_EQ(rx.counters().unexpected, 4u);

  // A sender not waiting for flow control ignores one.
  IsoTpSender idle(link_a());
  flow.id = link_a().rx_id;
  EXPECT_EQ(idle.on_frame(flow, 0), IsoTpStatus::kUnexpected);
  EXPECT_EQ(idle.start(msg.data(), 0, 0), IsoTpStatus::kBadArgument);
  idle.start(msg.data(), 300, 0);
  EXPECT_EQ(idle.start(msg.data(), 300, 0), IsoTpStatus::kBusy);
}

TEST(IsoTp, HeldReceiverSendsWaitThenContinues) {
  const auto msg = pattern(400);
  std::vector<uint8_t> buf(400);
  IsoTpSender tx(link_a());
  IsoTpReceiver rx(link_b(), buf.data(), buf.size());
  rx.hold(true);
  IsoTpReply out, fc;
  tx.start(msg.data(), msg.size(), 0);
  tx.poll(0, &out);
  ASSERT_EQ(rx.on_frame(out.frame, 0, &fc), IsoTpStatus::kInProgress);
  ASSERT_TRUE(fc.valid);
  EXPECT_EQ(fc.frame.data[0], 0x31) << "WAIT";
  EXPECT_EQ(tx.on_frame(fc.frame, 0), IsoTpStatus::kInProgress);
  // Half a timeout later the receiver repeats WAIT so the sender's N_Bs does not expire.
  ASSERT_EQ(rx.poll(500'000, &fc), IsoTpStatus::kInProgress);
  ASSERT_TRUE(fc.valid);
  EXPECT_EQ(fc.frame.data[0], 0x31);
  tx.on_frame(fc.frame, 500'000);
  EXPECT_EQ(tx.poll(1'200'000, &out), IsoTpStatus::kInProgress) << "WAIT restarted N_Bs";
  rx.hold(false);
  ASSERT_EQ(rx.poll(1'200'000, &fc), IsoTpStatus::kInProgress);
  ASSERT_TRUE(fc.valid);
  EXPECT_EQ(fc.frame.data[0], 0x30) << "CTS once released";
  tx.on_frame(fc.frame, 1'200'000);
  IsoTpStatus s = IsoTpStatus::kInProgress;
  while (s == IsoTpStatus::kInProgress) {
    tx.poll(1'200'000, &out);
    s = rx.on_frame(out.frame, 1'200'000, &fc);
  }
  EXPECT_EQ(s, IsoTpStatus::kComplete);
  EXPECT_TRUE(std::equal(msg.begin(), msg.end(), rx.data()));
}

TEST(IsoTp, SenderGivesUpAfterTooManyWaits) {
  IsoTpLink a = link_a();
  a.max_wait_frames = 2;
  const auto msg = pattern(100);
  IsoTpSender tx(a);
  IsoTpReply out;
  tx.start(msg.data(), msg.size(), 0);
  tx.poll(0, &out);
  CanFrame wait;
  wait.id = a.rx_id;
  wait.len = 8;
  wait.data[0] = 0x31;
  EXPECT_EQ(tx.on_frame(wait, 0), IsoTpStatus::kInProgress);
  EXPECT_EQ(tx.on_frame(wait, 0), IsoTpStatus::kInProgress);
  EXPECT_EQ(tx.on_frame(wait, 0), IsoTpStatus::kWaitLimit);
  EXPECT_EQ(tx.counters().wait_limits, 1u);
}

TEST(IsoTp, StMinEncoding) {
  EXPECT_EQ(st_min_us(0x00), 0u);
  EXPECT_EQ(st_min_us(0x7F), 127000u);
  EXPECT_EQ(st_min_us(0xF1), 100u);
  EXPECT_EQ(st_min_us(0xF9), 900u);
  EXPECT_EQ(st_min_us(0x80), 127000u) << "reserved values mean the maximum";
  EXPECT_EQ(st_min_us(0xFA), 127000u);
}
