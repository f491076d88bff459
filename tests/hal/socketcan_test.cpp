// SocketCAN on vcan0: the bus contract against a real kernel CAN stack, plus what only a
// kernel interface shows. Needs AF_CAN: run inside User-mode Linux (tests/uml/run-in-uml.sh,
// ctest label "vcan"); elsewhere every test skips with the reason.
#include <gtest/gtest.h>

#include "bus_contract.hpp"
#include "hal/linux/open_bus.hpp"
#include "hal/linux/socketcan_bus.hpp"

using namespace curio::hal;
using namespace curio::hal::test;

namespace {

// Set inside User-mode Linux by tests/uml: there, a missing AF_CAN is a failure.
bool vcan_required() { return std::getenv("CURIO_REQUIRE_VCAN") != nullptr; }

const char* iface() {
  const char* env = std::getenv("CURIO_VCAN");
  return env ? env : "vcan0";
}

BusBackend socketcan_backend() {
  return {"socketcan",
          [] {
            return std::function<std::unique_ptr<CanBus>(std::string*)>(
                [](std::string* why) -> std::unique_ptr<CanBus> {
                  return open_bus(std::string("socketcan:") + iface(), why);
                });
          },
          vcan_required()};
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(SocketCan, BusContract, ::testing::Values(socketcan_backend()),
                         [](const auto& info) { return info.param.name; });

TEST(SocketCan, FdInterfaceIsDetectedAndErrorFramesAreOptIn) {
  std::string why;
  auto bus = SocketCanBus::open(iface(), SocketCanOptions{true}, &why);
  if (!bus && vcan_required()) FAIL() << "SocketCAN unavailable: " << why;
  if (!bus) GTEST_SKIP() << "SocketCAN unavailable: " << why;
  EXPECT_TRUE(bus->fd_capable()) << iface() << " should have MTU 72 (CAN FD)";
  EXPECT_EQ(bus->state(), BusState::kErrorActive);
}

TEST(SocketCan, MissingInterfaceIsAClearError) {
  std::string why;
  auto bus = SocketCanBus::open("nosuchcan7", SocketCanOptions{}, &why);
  EXPECT_EQ(bus, nullptr);
  EXPECT_FALSE(why.empty());
  EXPECT_NE(why.find("socketcan:nosuchcan7"), std::string::npos) << why;
}
