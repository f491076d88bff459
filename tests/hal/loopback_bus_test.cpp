// The in-process loopback bus: the bus contract plus deterministic fault injection (paused
// wire with deadlines, bus-off, receive overrun) and use across threads.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "tests/hal/bus_contract.hpp"
#include "hal/host/loopback_bus.hpp"

using namespace curio::hal;
using namespace curio::hal::test;

namespace {

// `classic`: every endpoint a classic-only node.
BusBackend loopback_backend(bool classic) {
  return {classic ? "loopback_classic" : "loopback",
          [classic] {
            auto bus = LoopbackBus::create();
            return std::function<std::unique_ptr<CanBus>(std::string*)>(
                [bus, classic](std::string*) -> std::unique_ptr<CanBus> {
                  return bus->open(!classic);
                });
          },
          false, !classic};
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(Loopback, BusContract,
                         ::testing::Values(loopback_backend(false), loopback_backend(true)),
                         [](const auto& info) { return info.param.name; });

TEST(LoopbackBus, PausedWireDropsFramesWhoseDeadlinePassed) {
  ManualClock clock(1000);
  auto bus = LoopbackBus::create(&clock);
  auto a = bus->open();
  auto b = bus->open();
  bus->set_tx_paused(true);
  ASSERT_EQ(a->send(frame_of(0x10, 1), 1500), CanStatus::kOk);  // dies at t=1500
  ASSERT_EQ(a->send(frame_of(0x11, 1), 5000), CanStatus::kOk);  // survives
  ASSERT_EQ(b->send(frame_of(0x12, 1), 1200), CanStatus::kOk);  // dies
  CanFrame f;
  EXPECT_EQ(b->receive(&f), CanStatus::kEmpty) << "nothing moves while paused";
  clock.set_us(2000);
  bus->set_tx_paused(false);
  ASSERT_EQ(b->receive(&f), CanStatus::kOk);
  EXPECT_EQ(f.id, 0x11u);
  EXPECT_EQ(a->receive(&f), CanStatus::kEmpty);
  EXPECT_EQ(a->stats().tx_timedout, 1u);
  EXPECT_EQ(a->stats().tx_frames, 1u);
  EXPECT_EQ(b->stats().tx_timedout, 1u);
}

TEST(LoopbackBus, PausedWireQueueFullSaysWouldBlock) {
  auto bus = LoopbackBus::create();
  auto a = bus->open();
  bus->set_tx_paused(true);
  const uint64_t deadline = a->now_us() + 10'000'000;
  for (size_t i = 0; i < LoopbackBus::kPendingDepth; ++i) {
    ASSERT_EQ(a->send(frame_of(0x10, 1), deadline), CanStatus::kOk);
  }
  EXPECT_EQ(a->send(frame_of(0x10, 1), deadline), CanStatus::kWouldBlock);
  EXPECT_EQ(a->stats().tx_rejected, 1u);
}

TEST(LoopbackBus, BusOffNodeCannotSend) {
  auto bus = LoopbackBus::create();
  auto a = bus->open();
  auto b = bus->open();
  a->force_state(BusState::kBusOff);
  EXPECT_EQ(a->state(), BusState::kBusOff);
  EXPECT_EQ(a->send(frame_of(0x10, 1), a->now_us() + 1000), CanStatus::kBusOff);
  EXPECT_EQ(a->stats().bus_off_events, 1u);
  CanFrame f;
  EXPECT_EQ(b->receive(&f), CanStatus::kEmpty);
  ASSERT_EQ(b->send(frame_of(0x11, 1), b->now_us() + 1000), CanStatus::kOk);
  EXPECT_EQ(a->receive(&f), CanStatus::kEmpty) << "a bus-off node hears nothing either";
  a->force_state(BusState::kErrorActive);  // recovery
  EXPECT_EQ(a->send(frame_of(0x10, 1), a->now_us() + 1000), CanStatus::kOk);
  EXPECT_EQ(b->receive(&f), CanStatus::kOk);
}

TEST(LoopbackBus, FramesOfAClosedEndpointDoNotOutliveIt) {
  auto bus = LoopbackBus::create();
  auto a = bus->open();
  auto b = bus->open();
  bus->set_tx_paused(true);
  ASSERT_EQ(a->send(frame_of(0x10, 1), a->now_us() + 1'000'000), CanStatus::kOk);
  ASSERT_EQ(b->send(frame_of(0x20, 1), b->now_us() + 1'000'000), CanStatus::kOk);
  a.reset();
  auto c = bus->open();  // may take a's slot
  bus->set_tx_paused(false);
  auto got = collect(*c, 2, 0);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].id, 0x20u);
  EXPECT_EQ(c->stats().tx_frames, 0u) << "a's queued frame is not c's";
}

TEST(LoopbackBus, ReceiveOverrunIsCounted) {
  auto bus = LoopbackBus::create();
  auto a = bus->open();
  auto b = bus->open();
  std::vector<CanFrame> flood(LoopbackBus::kRxDepth + 10, frame_of(0x10, 8));
  ASSERT_EQ(a->send_batch(flood.data(), flood.size(), a->now_us() + 1'000'000, nullptr),
            CanStatus::kOk);
  EXPECT_EQ(b->stats().rx_dropped, 10u);
  EXPECT_EQ(collect(*b, flood.size(), 0).size(), LoopbackBus::kRxDepth);
}

TEST(LoopbackBus, EndpointsAreLimitedAndReusable) {
  auto bus = LoopbackBus::create();
  std::vector<std::unique_ptr<LoopbackEndpoint>> eps;
  for (size_t i = 0; i < LoopbackBus::kMaxEndpoints; ++i) eps.push_back(bus->open());
  EXPECT_EQ(bus->open(), nullptr);
  eps.pop_back();
  EXPECT_NE(bus->open(), nullptr);
}

TEST(LoopbackBus, NamedBusesConnectSeparatelyOpenedEndpoints) {
  auto a = named_loopback_bus("t1")->open();
  auto b = named_loopback_bus("t1")->open();
  auto other = named_loopback_bus("t2")->open();
  ASSERT_EQ(a->send(frame_of(0x55, 2), a->now_us() + 1000), CanStatus::kOk);
  CanFrame f;
  EXPECT_EQ(b->receive(&f), CanStatus::kOk);
  EXPECT_EQ(other->receive(&f), CanStatus::kEmpty);
}

TEST(LoopbackBus, WaitWakesAcrossThreads) {
  auto bus = LoopbackBus::create();
  auto a = bus->open();
  auto b = bus->open();
  std::thread sender([&] {
    for (int i = 0; i < 1000; ++i)
      a->send(frame_of(0x10, 8, false, false, static_cast<uint8_t>(i)), a->now_us() + 1'000'000);
  });
  auto got = collect(*b, 1000, 5'000'000);
  sender.join();
  ASSERT_EQ(got.size(), 1000u);
  for (int i = 0; i < 1000; ++i)
    EXPECT_TRUE(same_frame(got[i], frame_of(0x10, 8, false, false, static_cast<uint8_t>(i))));
}

TEST(SendAll, SendsEveryFrameInOrder) {
  auto bus = LoopbackBus::create();
  auto a = bus->open();
  auto b = bus->open();
  CanFrame frames[5];
  for (uint32_t i = 0; i < 5; ++i) frames[i] = frame_of(0x20 + i, 1);
  size_t sent = 99;
  ASSERT_EQ(send_all(*a, frames, 5, a->now_us() + 1'000'000, &sent), CanStatus::kOk);
  EXPECT_EQ(sent, 5u);
  for (uint32_t i = 0; i < 5; ++i) {
    CanFrame f;
    ASSERT_EQ(b->receive(&f), CanStatus::kOk);
    EXPECT_EQ(f.id, 0x20u + i);
  }
}

TEST(SendAll, AFullQueueIsWaitedOutUntilTheDeadlineThenTheRefusedFrameIsNamed) {
  auto bus = LoopbackBus::create();
  auto a = bus->open();
  bus->set_tx_paused(true);  // the wire never drains: the queue stays full
  std::vector<CanFrame> frames(LoopbackBus::kPendingDepth + 3, frame_of(0x10, 1));
  size_t sent = 0;
  const CanStatus s =
      send_all(*a, frames.data(), frames.size(), a->now_us() + 20'000, &sent);
  EXPECT_EQ(s, CanStatus::kDeadlineExpired);
  EXPECT_EQ(sent, LoopbackBus::kPendingDepth) << "frames[sent] is the one refused";
}
