// The host's monotonic clock (std::chrono::steady_clock = CLOCK_MONOTONIC on Linux).
#pragma once
#include "hal/clock.hpp"

namespace curio::hal {

class SteadyClock final : public Clock {
 public:
  uint64_t now_us() const override;
  // One shared instance: backends given no clock use it.
  static const SteadyClock& instance();
};

}  // namespace curio::hal
