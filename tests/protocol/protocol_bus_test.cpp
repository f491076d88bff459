// Protocol over real buses: a 12,288-byte camera frame through the loopback and UDP buses,
// alone and under a flood of foreign frames that no decoder may accept.
#include <gtest/gtest.h>

#include "tests/hal/bus_test_util.hpp"
#include "tests/hal/camera_transfer.hpp"
#include "hal/host/loopback_bus.hpp"
#include "hal/linux/open_bus.hpp"

using namespace curio::hal;
using namespace curio::hal::test;
using curio::protocol::IsoTpStatus;

TEST(ProtocolOverBus, CameraFrameOverLoopback) {
  auto bus = LoopbackBus::create();
  auto camera = bus->open();
  auto controller = bus->open();
  const TransferResult r = transfer_image(*camera, *controller);
  ASSERT_EQ(r.status, IsoTpStatus::kComplete);
  EXPECT_EQ(r.image, test_image());
  EXPECT_EQ(camera->stats().tx_frames, 196u);
  EXPECT_EQ(controller->stats().tx_frames, 1u) << "one flow control (block size 0)";
}

TEST(ProtocolOverBus, CameraFrameSurvivesAFloodOfForeignFrames) {
  auto bus = LoopbackBus::create();
  auto camera = bus->open();
  auto controller = bus->open();
  auto flooder = bus->open();
  const TransferResult r = transfer_image(*camera, *controller, flooder.get(), 50);
  ASSERT_EQ(r.status, IsoTpStatus::kComplete);
  EXPECT_EQ(r.image, test_image());
  EXPECT_GE(r.foreign_seen, 9000u);
  EXPECT_EQ(r.foreign_accepted, 0u) << "no decoder may accept a foreign frame";
  EXPECT_EQ(r.rx_counters.sequence_errors + r.rx_counters.unexpected, 0u);
}

TEST(ProtocolOverBus, CameraFrameOverUdpUnderFlood) {
  const uint16_t base = free_udp_base(8);
  std::string why;
  const std::string url = "udp:127.0.0.1:" + std::to_string(base);
  auto camera = open_bus(url, &why);
  auto controller = open_bus(url, &why);
  auto flooder = open_bus(url, &why);
  ASSERT_TRUE(camera && controller && flooder) << why;
  const TransferResult r = transfer_image(*camera, *controller, flooder.get(), 10);
  ASSERT_EQ(r.status, IsoTpStatus::kComplete);
  EXPECT_EQ(r.image, test_image());
  EXPECT_EQ(r.foreign_accepted, 0u);
}

TEST(ProtocolOverBus, FloodFramesAreNeverOurs) {
  for (uint32_t k = 0; k < 200000; ++k) {
    const CanFrame f = foreign_frame(k);
    ASSERT_TRUE(is_valid(f)) << k;
    ASSERT_FALSE(any_decoder_accepts(f)) << k << " " << std::hex << f.id;
  }
}
