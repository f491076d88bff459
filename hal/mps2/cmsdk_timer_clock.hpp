// A monotonic microsecond hal::Clock from the CMSDK APB timer of the MPS2 boards (TIMER0 at
// 0x40000000, a 32-bit down-counter at the 25 MHz peripheral clock; QEMU runs it on its
// virtual clock, which without -icount follows the host's time). The counter wraps every
// 171 s; now_us() extends it to 64 bits, so it must be read at least that often (the
// controller reads it every control period).
#pragma once
#include <cstdint>

#include "hal/clock.hpp"

namespace curio::hal::mps2 {

inline constexpr uintptr_t kTimer0Base = 0x40000000u;
inline constexpr uint32_t kPeripheralClockHz = 25'000'000u;

class CmsdkTimerClock final : public Clock {
 public:
  explicit CmsdkTimerClock(uintptr_t base = kTimer0Base) : base_(base) {}

  // Starts the timer free-running from 0xFFFFFFFF (no interrupt).
  void init();

  uint64_t now_us() const override;

 private:
  volatile uint32_t* reg(uint32_t offset) const {
    return reinterpret_cast<volatile uint32_t*>(base_ + offset);
  }
  uintptr_t base_;
  mutable uint32_t last_ = 0xFFFFFFFFu;  // counter at the previous reading
  mutable uint64_t ticks_ = 0;           // ticks since init()
};

}  // namespace curio::hal::mps2
