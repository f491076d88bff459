// hal::SlcanBus (SLCAN over a serial port) against an in-memory serial port: lines out,
// frames in, filters, deadlines, classic-only links, malformed lines counted, and a full
// receive queue holding bytes back in the port instead of losing them.
#include <gtest/gtest.h>

#include <deque>
#include <string>

#include "hal/clock.hpp"
#include "hal/slcan/slcan_bus.hpp"

using namespace curio::hal;
using curio::protocol::SlcanMode;

namespace {

// A serial line in memory: what the bus writes goes to `written`; `incoming` is what the
// other end sent. TX takes `tx_room` bytes before it reports full; each read advances the
// clock by 10 µs (time passes while the bus polls).
struct MemorySerial final : SerialPort {
  std::string written;
  std::deque<uint8_t> incoming;
  size_t tx_room = SIZE_MAX;
  ManualClock* clock = nullptr;

  bool try_write(uint8_t b) override {
    if (tx_room == 0) return false;
    --tx_room;
    written.push_back(static_cast<char>(b));
    return true;
  }
  bool try_read(uint8_t* b) override {
    if (clock != nullptr) clock->advance_us(10);
    if (incoming.empty()) return false;
    *b = incoming.front();
    incoming.pop_front();
    return true;
  }
  void feed(const std::string& s) { incoming.insert(incoming.end(), s.begin(), s.end()); }
};

CanFrame classic(uint32_t id, std::initializer_list<uint8_t> bytes) {
  CanFrame f;
  EXPECT_TRUE(make_frame(&f, id, id > 0x7FF, false, std::data(bytes), bytes.size()));
  return f;
}

struct SlcanBusTest : ::testing::Test {
  ManualClock clock{1000};
  MemorySerial port;
  SlcanBus bus{&port, &clock, SlcanMode::kFd};
  void SetUp() override { port.clock = &clock; }
};

}  // namespace

TEST_F(SlcanBusTest, SendsOneLinePerFrame) {
  const CanFrame frames[2] = {classic(0x321, {0xDE, 0xAD, 0xBE, 0xEF}), classic(0x080, {1})};
  size_t accepted = 0;
  ASSERT_EQ(bus.send_batch(frames, 2, clock.now_us() + 100, &accepted), CanStatus::kOk);
  EXPECT_EQ(accepted, 2u);
  EXPECT_EQ(port.written, "t3214DEADBEEF\rt080101\r");
  EXPECT_EQ(bus.stats().tx_frames, 2u);
  EXPECT_EQ(bus.tx_bytes(), port.written.size());
}

TEST_F(SlcanBusTest, ReceivesFramesAndCountsMalformedLines) {
  port.feed("t1232AABB\rtXYZ\rO\rT18DAF1201FF\r");
  CanFrame out[4];
  size_t n = 0;
  ASSERT_EQ(bus.receive_batch(out, 4, &n), CanStatus::kOk);
  ASSERT_EQ(n, 2u);
  EXPECT_EQ(out[0].id, 0x123u);
  EXPECT_EQ(out[1].id, 0x18DAF120u);
  EXPECT_EQ(bus.stats().errors, 1u) << "tXYZ";
  EXPECT_EQ(bus.slcan_counters().commands, 1u) << "O";
  EXPECT_EQ(bus.receive_batch(out, 4, &n), CanStatus::kEmpty);
}

TEST_F(SlcanBusTest, WaitReadableTimesOutOnTheBusClock) {
  const uint64_t t0 = clock.now_us();
  EXPECT_EQ(bus.wait_readable(5000), CanStatus::kTimeout);
  EXPECT_GE(clock.now_us() - t0, 5000u);
  port.feed("t0800\r");
  CanFrame f;
  EXPECT_EQ(bus.receive(&f, 5000), CanStatus::kOk);
  EXPECT_EQ(f.id, 0x080u);
}

TEST_F(SlcanBusTest, AppliesAcceptanceFilters) {
  const CanFilter only_tpdo{0x180, 0x780, IdType::kStandard};
  ASSERT_EQ(bus.set_filters(&only_tpdo, 1), CanStatus::kOk);
  port.feed("t1816010203040506\rt7010\r");
  CanFrame out[4];
  size_t n = 0;
  ASSERT_EQ(bus.receive_batch(out, 4, &n), CanStatus::kOk);
  ASSERT_EQ(n, 1u);
  EXPECT_EQ(out[0].id, 0x181u);
  EXPECT_EQ(bus.stats().rx_filtered, 1u);
}

TEST_F(SlcanBusTest, ExpiredDeadlineAndUnencodableFramesAreRefused) {
  const CanFrame f = classic(0x123, {1});
  EXPECT_EQ(bus.send(f, clock.now_us() - 1), CanStatus::kDeadlineExpired);
  EXPECT_TRUE(port.written.empty());
  CanFrame err = f;
  err.flags = kFlagError;
  EXPECT_EQ(bus.send(err, clock.now_us() + 100), CanStatus::kNotSupported);
  CanFrame bad = f;
  bad.len = 9;
  EXPECT_EQ(bus.send(bad, clock.now_us() + 100), CanStatus::kInvalidFrame);
  EXPECT_EQ(bus.stats().tx_rejected, 3u);
}

TEST(SlcanBus, ClassicLinkRefusesFdFrames) {
  ManualClock clock;
  MemorySerial port;
  SlcanBus bus(&port, &clock, SlcanMode::kClassic);
  uint8_t payload[48] = {};
  CanFrame fd;
  ASSERT_TRUE(make_frame(&fd, 0x2A0, false, true, payload, sizeof payload));
  EXPECT_EQ(bus.send(fd, 100), CanStatus::kNotSupported);
  port.feed("d2A00\rt2A00\r");
  CanFrame out[2];
  size_t n = 0;
  ASSERT_EQ(bus.receive_batch(out, 2, &n), CanStatus::kOk);
  EXPECT_EQ(n, 1u);
  EXPECT_EQ(bus.slcan_counters().unsupported, 1u);
}

TEST_F(SlcanBusTest, FullReceiveQueueLeavesBytesInThePort) {
  std::string lines;
  for (size_t i = 0; i < SlcanBus::kRxQueueFrames + 10; ++i)
    lines += "t0011" + std::string(i % 2 ? "AA" : "55") + "\r";
  port.feed(lines);
  EXPECT_EQ(bus.wait_readable(0), CanStatus::kOk);
  EXPECT_EQ(port.incoming.size(), 10u * 8) << "the last ten lines wait in the port";
  CanFrame out[SlcanBus::kRxQueueFrames + 10];
  size_t n = 0, total = 0;
  while (bus.receive_batch(out, SlcanBus::kRxQueueFrames + 10, &n) == CanStatus::kOk) total += n;
  EXPECT_EQ(total, SlcanBus::kRxQueueFrames + 10);
  EXPECT_EQ(bus.stats().rx_dropped, 0u);
}

TEST_F(SlcanBusTest, DrainsTheReceiverWhileTheTransmitterIsFull) {
  port.tx_room = 3;  // the line stalls after 3 bytes...
  port.feed("t0800\r");
  // ...and send_batch would spin forever; give it room after the receive side was drained.
  struct Unstick final : SerialPort {
    MemorySerial* p;
    int stalls = 0;
    bool try_write(uint8_t b) override {
      if (!p->try_write(b)) {
        if (++stalls > 2) p->tx_room = SIZE_MAX;
        return false;
      }
      return true;
    }
    bool try_read(uint8_t* b) override { return p->try_read(b); }
  } unstick;
  unstick.p = &port;
  SlcanBus b2(&unstick, &clock, SlcanMode::kFd);
  ASSERT_EQ(b2.send(classic(0x123, {0xAA}), clock.now_us() + 1000), CanStatus::kOk);
  EXPECT_EQ(port.written, "t1231AA\r");
  CanFrame f;
  EXPECT_EQ(b2.receive(&f), CanStatus::kOk) << "the frame read while TX was full";
  EXPECT_EQ(f.id, 0x080u);
}
