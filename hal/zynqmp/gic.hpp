// The ZynqMP APU's interrupt controller (GIC-400, GICv2: distributor at 0xF9010000, CPU
// interface at 0xF9020000) for one core in the Secure state, as QEMU's xlnx-zcu102 models it:
// every interrupt stays in Group 0 and is signalled as IRQ (GICC_CTLR.FIQEn = 0). A handler
// table of fixed size (no heap) maps interrupt IDs to handlers; curio_irq_dispatch (called by
// toolchain/boards/zcu102/startup.S on every IRQ) acknowledges, dispatches and ends each one.
// Interrupt IDs: SGIs 0-15, PPIs 16-31 (the virtual timer is 27), SPIs from 32 (CAN0 is
// SPI 23 = ID 55, CAN1 SPI 24 = ID 56; UG1085 table 13-1). Firmware-clean.
#pragma once
#include <cstdint>

namespace curio::hal::zynqmp {

inline constexpr uintptr_t kGicDistBase = 0xF9010000u;
inline constexpr uintptr_t kGicCpuBase = 0xF9020000u;
inline constexpr uint32_t kGicIds = 192;  // 32 private + 160 shared (QEMU's GIC_NUM_SPI_INTR)
inline constexpr uint32_t kIrqVirtualTimer = 27;
inline constexpr uint32_t kIrqCan0 = 32 + 23;
inline constexpr uint32_t kIrqCan1 = 32 + 24;

using IrqHandler = void (*)(void* context);

struct GicCounters {
  uint32_t dispatched = 0;
  uint32_t spurious = 0;   // IAR read 1023: nothing pending any more
  uint32_t unhandled = 0;  // an ID without a handler (it is disabled)
};

class Gic {
 public:
  // Distributor and CPU interface on, every interrupt disabled, priority mask open.
  static void init();
  // Installs `handler` for `id` at `priority` (0 highest .. 0xF0), routed to core 0, level
  // sensitive, and enables it. False for an ID out of range.
  static bool attach(uint32_t id, IrqHandler handler, void* context, uint8_t priority = 0xA0);
  static void enable(uint32_t id);
  static void disable(uint32_t id);
  static const GicCounters& counters();
};

// CPSR.I: the core takes IRQs or not. IrqLock masks them for a scope (nesting allowed).
inline void irq_enable() {
  __asm__ volatile("cpsie i" ::: "memory");
}
inline void irq_disable() {
  __asm__ volatile("cpsid i" ::: "memory");
}

class IrqLock {
 public:
  IrqLock() {
    __asm__ volatile("mrs %0, cpsr" : "=r"(saved_)::"memory");
    irq_disable();
  }
  ~IrqLock() {
    if ((saved_ & 0x80u) == 0) irq_enable();
  }
  IrqLock(const IrqLock&) = delete;
  IrqLock& operator=(const IrqLock&) = delete;

 private:
  uint32_t saved_ = 0;
};

// Waits for an interrupt with IRQs masked (a pending one wakes the core), then lets it be
// taken: call with IRQs masked after checking the condition, so a wake-up is never lost.
inline void wait_for_interrupt_then_take() {
  __asm__ volatile("dsb\n wfi" ::: "memory");
  irq_enable();
  __asm__ volatile("isb" ::: "memory");
  irq_disable();
}

}  // namespace curio::hal::zynqmp

extern "C" void curio_irq_dispatch();
