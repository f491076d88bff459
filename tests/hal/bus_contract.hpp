// Behaviour every CanBus backend promises, run against each of them (loopback, UDP, and
// SocketCAN inside User-mode Linux). A backend provides a factory of endpoints on one bus.
#pragma once
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>

#include "tests/hal/bus_test_util.hpp"
#include "hal/can_bus.hpp"

namespace curio::hal::test {

struct BusBackend {
  std::string name;
  // Returns a function that opens endpoints on one fresh bus (null endpoint: backend missing,
  // *why says why).
  std::function<std::function<std::unique_ptr<CanBus>(std::string* why)>()> new_bus;
  bool required = false;  // fail instead of skipping when the backend cannot open
  bool fd = true;         // its endpoints carry CAN FD (false: a classic-only bus)
};

inline void PrintTo(const BusBackend& b, std::ostream* os) {
  *os << b.name;
}

class BusContract : public ::testing::TestWithParam<BusBackend> {
 protected:
  void SetUp() override {
    open_ = GetParam().new_bus();
    std::string why;
    a_ = open_(&why);
    if (!a_ && GetParam().required) FAIL() << GetParam().name << " backend unavailable: " << why;
    if (!a_) GTEST_SKIP() << GetParam().name << " backend unavailable: " << why;
    b_ = open_(&why);
    ASSERT_TRUE(b_) << why;
  }
  uint64_t soon() const { return a_->now_us() + 1'000'000; }
  // The backend's largest frame: FD 64 bytes, or classic 8.
  bool fd() const { return GetParam().fd; }
  size_t fd_len() const { return fd() ? 64 : 8; }

  std::function<std::unique_ptr<CanBus>(std::string*)> open_;
  std::unique_ptr<CanBus> a_, b_;
};

}  // namespace curio::hal::test
