// Instruction counts on the Cortex-M7 under QEMU `-icount shift=0`: there one guest
// instruction takes 1 ns of virtual time, and SysTick on the processor clock (mps2-an500:
// 25 MHz) counts down once per 40 ns, i.e. once per 40 instructions. QEMU has no DWT cycle
// counter (CYCCNT reads 0) and its SYS_ELAPSED follows the host's clock, so SysTick is the
// deterministic counter. Resolution 40 instructions; one interval must stay below 2^24 ticks
// (671 M instructions). QEMU is not cycle-accurate: these are instructions, not cycles.
#pragma once
#include <cstdint>

namespace curio::test {

class InstructionCounter {
 public:
  static constexpr uint32_t kInstructionsPerTick = 40;  // 1 ns per instruction, 40 ns per tick
  static constexpr uint32_t kMask = 0x00FFFFFFu;

  // SysTick: reload 2^24 − 1, processor clock, no interrupt.
  static void start() {
    reg(kRvr) = kMask;
    reg(kCvr) = 0u;
    reg(kCsr) = 0x5u;
  }
  static uint32_t now() { return reg(kCvr); }
  // Instructions between two now() readings (the counter counts down and wraps).
  static uint32_t instructions(uint32_t begin, uint32_t end) {
    return ((begin - end) & kMask) * kInstructionsPerTick;
  }

  // A loop of exactly 2 instructions per iteration (subs + bne), for calibration.
  static void spin(uint32_t iterations) {
    __asm__ volatile(
        "1: subs %0, %0, #1\n"
        "   bne 1b\n"
        : "+r"(iterations)
        :
        : "cc");
  }

 private:
  static constexpr uintptr_t kCsr = 0xE000E010u, kRvr = 0xE000E014u, kCvr = 0xE000E018u;
  static volatile uint32_t& reg(uintptr_t address) {
    return *reinterpret_cast<volatile uint32_t*>(address);
  }
};

}  // namespace curio::test
