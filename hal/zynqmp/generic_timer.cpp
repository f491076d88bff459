// Generic timer clock and idle alarm (generic_timer.hpp).
#include "hal/zynqmp/generic_timer.hpp"

#include "hal/zynqmp/gic.hpp"

namespace curio::hal::zynqmp {
namespace {

uint64_t read_cntvct() {
  uint32_t lo = 0, hi = 0;
  __asm__ volatile("isb\n mrrc p15, 1, %0, %1, c14" : "=r"(lo), "=r"(hi)::"memory");
  return static_cast<uint64_t>(hi) << 32 | lo;
}
void write_cntv_cval(uint64_t v) {
  const uint32_t lo = static_cast<uint32_t>(v), hi = static_cast<uint32_t>(v >> 32);
  __asm__ volatile("mcrr p15, 3, %0, %1, c14" ::"r"(lo), "r"(hi) : "memory");
}
void write_cntv_ctl(uint32_t v) {
  __asm__ volatile("mcr p15, 0, %0, c14, c3, 1\n isb" ::"r"(v) : "memory");
}
constexpr uint32_t kCtlEnable = 1u;
constexpr uint32_t kCtlMask = 2u;

}  // namespace

void GenericTimer::init() {
  uint32_t f = 0;
  __asm__ volatile("mrc p15, 0, %0, c14, c0, 0" : "=r"(f));
  if (f != 0) frequency_hz_ = f;
  write_cntv_ctl(0);
  Gic::attach(kIrqVirtualTimer, &GenericTimer::on_alarm, this);
}

uint64_t GenericTimer::ticks() const {
  return read_cntvct();
}

uint64_t GenericTimer::now_us() const {
  const uint64_t t = read_cntvct();
  return t / frequency_hz_ * 1'000'000u + (t % frequency_hz_) * 1'000'000u / frequency_hz_;
}

void GenericTimer::idle_until(uint64_t until_us) {
  const uint64_t now = now_us();
  if (now >= until_us) return;
  const uint64_t dt = until_us - now;
  const uint64_t dticks =
      dt / 1'000'000u * frequency_hz_ + (dt % 1'000'000u) * frequency_hz_ / 1'000'000u + 1;
  write_cntv_cval(read_cntvct() + dticks);
  write_cntv_ctl(kCtlEnable);
  wait_for_interrupt_then_take();
  write_cntv_ctl(0);
}

void GenericTimer::on_alarm(void* self) {
  write_cntv_ctl(kCtlMask);  // level interrupt: masked until the next idle_until re-arms it
  auto* t = static_cast<GenericTimer*>(self);
  t->alarms_ = t->alarms_ + 1;
}

}  // namespace curio::hal::zynqmp
