// The socket backends' shared TX backlog, against a fake transport that takes only as many
// frames as it is told to: order, deadline expiry in the backlog, backlog overflow.
#include <gtest/gtest.h>

#include <vector>

#include "tests/hal/bus_test_util.hpp"
#include "hal/host/queued_bus.hpp"

using namespace curio::hal;
using namespace curio::hal::test;

namespace {

class FakeTransportBus final : public QueuedBus {
 public:
  explicit FakeTransportBus(const Clock* clock) : QueuedBus(clock) {}
  size_t room = 0;  // frames the transport accepts before saying EAGAIN
  bool classic_only = false;
  std::vector<CanFrame> wire;

  CanStatus receive_batch(CanFrame*, size_t, size_t* n) override {
    flush_backlog();
    *n = 0;
    return CanStatus::kEmpty;
  }
  CanStatus wait_readable(uint64_t) override { return CanStatus::kTimeout; }
  CanStatus set_filters(const CanFilter*, size_t) override { return CanStatus::kOk; }
  bool carries_fd() const override { return !classic_only; }
  void go_bus_off() { state_ = BusState::kBusOff; }

 protected:
  CanStatus transmit(const CanFrame* frames, size_t count, size_t* sent) override {
    *sent = std::min(count, room);
    room -= *sent;
    wire.insert(wire.end(), frames, frames + *sent);
    return *sent == count ? CanStatus::kOk : CanStatus::kWouldBlock;
  }
  bool supports(const CanFrame& f) const override { return !classic_only || !f.fd(); }
};

}  // namespace

TEST(QueuedBus, FramesTheTransportCannotTakeWaitInOrder) {
  ManualClock clock(100);
  FakeTransportBus bus(&clock);
  bus.room = 2;
  std::vector<CanFrame> frames;
  for (uint32_t i = 0; i < 5; ++i) frames.push_back(frame_of(i, 1));
  size_t accepted = 0;
  ASSERT_EQ(bus.send_batch(frames.data(), 5, 1000, &accepted), CanStatus::kOk);
  EXPECT_EQ(accepted, 5u) << "taken: 2 on the wire, 3 in the backlog";
  EXPECT_EQ(bus.wire.size(), 2u);
  EXPECT_EQ(bus.backlog_size(), 3u);
  // A later frame must queue behind the backlog even if the transport has room now.
  bus.room = 1;
  ASSERT_EQ(bus.send(frame_of(9, 1), 1000), CanStatus::kOk);
  bus.room = 10;
  size_t n = 0;
  CanFrame out;
  bus.receive_batch(&out, 1, &n);  // any call flushes
  ASSERT_EQ(bus.wire.size(), 6u);
  const uint32_t order[] = {0, 1, 2, 3, 4, 9};
  for (size_t i = 0; i < 6; ++i) EXPECT_EQ(bus.wire[i].id, order[i]);
  EXPECT_EQ(bus.stats().tx_frames, 6u);
}

TEST(QueuedBus, BackloggedFramesPastTheirDeadlineAreDropped) {
  ManualClock clock(100);
  FakeTransportBus bus(&clock);
  ASSERT_EQ(bus.send(frame_of(1, 1), 200), CanStatus::kOk);
  ASSERT_EQ(bus.send(frame_of(2, 1), 900), CanStatus::kOk);
  clock.set_us(500);
  bus.room = 10;
  size_t n = 0;
  CanFrame out;
  bus.receive_batch(&out, 1, &n);
  ASSERT_EQ(bus.wire.size(), 1u);
  EXPECT_EQ(bus.wire[0].id, 2u);
  EXPECT_EQ(bus.stats().tx_timedout, 1u);
}

TEST(QueuedBus, FullBacklogSaysWouldBlockAndCountsHowManyWereTaken) {
  ManualClock clock(0);
  FakeTransportBus bus(&clock);
  std::vector<CanFrame> frames(QueuedBus::kBacklogDepth + 5, frame_of(1, 1));
  size_t accepted = 0;
  EXPECT_EQ(bus.send_batch(frames.data(), frames.size(), 1000, &accepted), CanStatus::kWouldBlock);
  EXPECT_EQ(accepted, QueuedBus::kBacklogDepth);
  EXPECT_EQ(bus.stats().tx_rejected, 1u);
}

TEST(QueuedBus, UnsupportedAndBusOffAreRefused) {
  ManualClock clock(0);
  FakeTransportBus bus(&clock);
  bus.room = 10;
  bus.classic_only = true;
  const CanFrame frames[] = {frame_of(1, 8), frame_of(2, 64, true)};
  size_t accepted = 0;
  EXPECT_EQ(bus.send_batch(frames, 2, 1000, &accepted), CanStatus::kNotSupported);
  EXPECT_EQ(accepted, 1u) << "the classic frame before the FD one went out";
  bus.go_bus_off();
  EXPECT_EQ(bus.send(frames[0], 1000), CanStatus::kBusOff);
  EXPECT_EQ(bus.wire.size(), 1u);
}
