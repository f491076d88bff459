// Monotonic microsecond clock behind the HAL. Firmware supplies a timer-backed one; host
// backends use the OS monotonic clock; tests drive a ManualClock for determinism.
#pragma once
#include <cstdint>

namespace curio::hal {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual uint64_t now_us() const = 0;
};

// Time moves only when told to: deadline and timeout tests without real waiting.
class ManualClock final : public Clock {
 public:
  explicit ManualClock(uint64_t start_us = 0) : now_(start_us) {}
  uint64_t now_us() const override { return now_; }
  void set_us(uint64_t t) { now_ = t; }
  void advance_us(uint64_t dt) { now_ += dt; }

 private:
  uint64_t now_;
};

}  // namespace curio::hal
