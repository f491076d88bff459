// The Arm generic timer of the Cortex-A53 (AArch32 CP15 view) as a monotonic hal::Clock, and
// its virtual timer (PPI 27) as the wake-up alarm of an idle wait: the core sleeps in WFI until
// an interrupt (a CAN frame) or the alarm. QEMU runs the counter at 62.5 MHz (CNTFRQ) on its
// virtual clock, which follows the host's time. CNTVOFF is 0 (no EL2), so the virtual count
// is the physical one. Firmware-clean.
#pragma once
#include <cstdint>

#include "hal/clock.hpp"

namespace curio::hal::zynqmp {

class GenericTimer final : public Clock {
 public:
  // Reads CNTFRQ; attaches the alarm's interrupt (Gic::init() first).
  void init();

  uint64_t now_us() const override;
  uint64_t ticks() const;
  uint32_t frequency_hz() const { return frequency_hz_; }

  // Sleeps until an interrupt arrives or the clock reaches `until_us`, whichever is first
  // (returns at once if it has). Call with IRQs masked (IrqLock) after checking what is
  // awaited; returns with them masked.
  void idle_until(uint64_t until_us);

  uint32_t alarms() const { return alarms_; }

 private:
  static void on_alarm(void* self);
  uint32_t frequency_hz_ = 62'500'000u;
  volatile uint32_t alarms_ = 0;
};

}  // namespace curio::hal::zynqmp
