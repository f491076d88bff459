// SocketCAN on vcan0: the bus contract against a real kernel CAN stack, plus what only a
// kernel interface shows. Needs AF_CAN: run inside User-mode Linux (tests/uml/run-in-uml.sh,
// ctest label "vcan"); elsewhere every test skips with the reason.
#include <gtest/gtest.h>

#include "tests/hal/bus_contract.hpp"
#include "tests/hal/camera_transfer.hpp"
#include "hal/linux/open_bus.hpp"
#include "hal/linux/socketcan_bus.hpp"

using namespace curio::hal;
using namespace curio::hal::test;

namespace {

// Set inside User-mode Linux by tests/uml: there, a missing AF_CAN is a failure.
bool vcan_required() {
  return std::getenv("CURIO_REQUIRE_VCAN") != nullptr;
}

const char* iface() {
  const char* env = std::getenv("CURIO_VCAN");
  return env ? env : "vcan0";
}

// The classic interface (MTU 16) tests/uml/run-in-uml.sh creates beside vcan0.
const char* classic_iface() {
  const char* env = std::getenv("CURIO_VCAN_CLASSIC");
  return env ? env : "vcan_classic";
}

BusBackend socketcan_backend(bool classic) {
  const std::string name = classic ? classic_iface() : iface();
  return {classic ? "socketcan_classic" : "socketcan",
          [name] {
            return std::function<std::unique_ptr<CanBus>(std::string*)>(
                [name](std::string* why) -> std::unique_ptr<CanBus> {
                  return open_bus("socketcan:" + name, why);
                });
          },
          vcan_required(), !classic};
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(SocketCan, BusContract,
                         ::testing::Values(socketcan_backend(false), socketcan_backend(true)),
                         [](const auto& info) { return info.param.name; });

TEST(SocketCan, FdInterfaceIsDetectedAndErrorFramesAreOptIn) {
  std::string why;
  auto bus = SocketCanBus::open(iface(), SocketCanOptions{true}, &why);
  if (!bus && vcan_required()) FAIL() << "SocketCAN unavailable: " << why;
  if (!bus) GTEST_SKIP() << "SocketCAN unavailable: " << why;
  EXPECT_TRUE(bus->carries_fd()) << iface() << " should have MTU 72 (CAN FD)";
  EXPECT_EQ(bus->state(), BusState::kErrorActive);
}

TEST(SocketCan, MissingInterfaceIsAClearError) {
  std::string why;
  auto bus = SocketCanBus::open("nosuchcan7", SocketCanOptions{}, &why);
  EXPECT_EQ(bus, nullptr);
  EXPECT_FALSE(why.empty());
  EXPECT_NE(why.find("socketcan:nosuchcan7"), std::string::npos) << why;
}

// The camera frame over a real kernel interface under a flood of foreign frames, in the
// interface's profile: vcan0 (FD, 196 frames) and vcan_classic (MTU 16, 1,757 8-byte frames;
// the flood's FD frames cannot go there and are refused).
class SocketCanTransfer : public ::testing::TestWithParam<bool> {};

TEST_P(SocketCanTransfer, CameraFrameUnderFlood) {
  const bool classic = GetParam();
  std::string why;
  const std::string url = std::string("socketcan:") + (classic ? classic_iface() : iface());
  auto camera = open_bus(url, &why);
  if (!camera && vcan_required()) FAIL() << "SocketCAN unavailable: " << why;
  if (!camera) GTEST_SKIP() << "SocketCAN unavailable: " << why;
  auto controller = open_bus(url, &why);
  auto flooder = open_bus(url, &why);
  ASSERT_TRUE(controller && flooder) << why;
  ASSERT_EQ(camera->carries_fd(), !classic) << url << " should have MTU " << (classic ? 16 : 72);
  const uint64_t t0 = camera->now_us();
  const TransferResult r = transfer_image(*camera, *controller, flooder.get(), 10);
  const uint64_t t1 = camera->now_us();
  ASSERT_EQ(r.status, curio::protocol::IsoTpStatus::kComplete);
  EXPECT_EQ(r.image, test_image());
  EXPECT_EQ(r.foreign_accepted, 0u);
  EXPECT_EQ(r.image_frames, classic ? 1757u : 196u);
  std::printf("%s: camera frame with 10 foreign frames per data frame: %.1f ms\n", url.c_str(),
              (t1 - t0) * 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Profiles, SocketCanTransfer, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "classic" : "fd"; });
