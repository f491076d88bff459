#include "hal/host/steady_clock.hpp"

#include <chrono>

namespace curio::hal {

uint64_t SteadyClock::now_us() const {
  const auto t = std::chrono::steady_clock::now().time_since_epoch();
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(t).count());
}

const SteadyClock& SteadyClock::instance() {
  static const SteadyClock clock;
  return clock;
}

}  // namespace curio::hal
