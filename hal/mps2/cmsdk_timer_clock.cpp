// CMSDK APB timer as a 64-bit microsecond clock (cmsdk_timer_clock.hpp).
#include "hal/mps2/cmsdk_timer_clock.hpp"

namespace curio::hal::mps2 {

namespace {
constexpr uint32_t kCtrl = 0x00;
constexpr uint32_t kValue = 0x04;
constexpr uint32_t kReload = 0x08;
constexpr uint32_t kCtrlEnable = 1u << 0;
constexpr uint32_t kTicksPerUs = kPeripheralClockHz / 1'000'000u;
static_assert(kPeripheralClockHz % 1'000'000u == 0, "whole ticks per microsecond");
}  // namespace

void CmsdkTimerClock::init() {
  *reg(kCtrl) = 0;
  *reg(kReload) = 0xFFFFFFFFu;
  *reg(kValue) = 0xFFFFFFFFu;
  *reg(kCtrl) = kCtrlEnable;
  last_ = 0xFFFFFFFFu;
  ticks_ = 0;
}

uint64_t CmsdkTimerClock::now_us() const {
  const uint32_t v = *reg(kValue);
  ticks_ += static_cast<uint32_t>(last_ - v);  // down-counter: elapsed ticks, mod 2^32
  last_ = v;
  return ticks_ / kTicksPerUs;
}

}  // namespace curio::hal::mps2
