// GICv2 for one Secure core (gic.hpp).
#include "hal/zynqmp/gic.hpp"

namespace curio::hal::zynqmp {
namespace {

// Distributor
constexpr uint32_t kGicdCtlr = 0x000;
constexpr uint32_t kGicdIsenabler = 0x100;
constexpr uint32_t kGicdIcenabler = 0x180;
constexpr uint32_t kGicdIcpendr = 0x280;
constexpr uint32_t kGicdIpriorityr = 0x400;
constexpr uint32_t kGicdItargetsr = 0x800;
constexpr uint32_t kGicdIcfgr = 0xC00;
// CPU interface
constexpr uint32_t kGiccCtlr = 0x00;
constexpr uint32_t kGiccPmr = 0x04;
constexpr uint32_t kGiccBpr = 0x08;
constexpr uint32_t kGiccIar = 0x0C;
constexpr uint32_t kGiccEoir = 0x10;
constexpr uint32_t kSpurious = 1023;

volatile uint32_t* dist(uint32_t offset) {
  return reinterpret_cast<volatile uint32_t*>(kGicDistBase + offset);
}
volatile uint8_t* dist8(uint32_t offset) {
  return reinterpret_cast<volatile uint8_t*>(kGicDistBase + offset);
}
volatile uint32_t* cpu(uint32_t offset) {
  return reinterpret_cast<volatile uint32_t*>(kGicCpuBase + offset);
}

struct Slot {
  IrqHandler handler = nullptr;
  void* context = nullptr;
};
Slot g_slots[kGicIds];
GicCounters g_counters;

}  // namespace

void Gic::init() {
  *dist(kGicdCtlr) = 0;
  for (uint32_t i = 0; i < kGicIds / 32; ++i) {
    *dist(kGicdIcenabler + 4 * i) = 0xFFFFFFFFu;
    *dist(kGicdIcpendr + 4 * i) = 0xFFFFFFFFu;
  }
  *dist(kGicdCtlr) = 1u;  // Group 0 forwarding on
  *cpu(kGiccPmr) = 0xF0u;
  *cpu(kGiccBpr) = 0;
  *cpu(kGiccCtlr) = 1u;  // Group 0 signalling on, as IRQ (FIQEn = 0)
}

bool Gic::attach(uint32_t id, IrqHandler handler, void* context, uint8_t priority) {
  if (id >= kGicIds || handler == nullptr) return false;
  disable(id);
  g_slots[id].handler = handler;
  g_slots[id].context = context;
  *dist8(kGicdIpriorityr + id) = priority;
  if (id >= 32) {
    *dist8(kGicdItargetsr + id) = 0x01u;  // core 0
    volatile uint32_t* cfg = dist(kGicdIcfgr + 4 * (id / 16));
    *cfg = *cfg & ~(2u << (2 * (id % 16)));  // level sensitive
  }
  enable(id);
  return true;
}

void Gic::enable(uint32_t id) {
  if (id < kGicIds) *dist(kGicdIsenabler + 4 * (id / 32)) = 1u << (id % 32);
}

void Gic::disable(uint32_t id) {
  if (id < kGicIds) *dist(kGicdIcenabler + 4 * (id / 32)) = 1u << (id % 32);
}

const GicCounters& Gic::counters() {
  return g_counters;
}

}  // namespace curio::hal::zynqmp

extern "C" void curio_irq_dispatch() {
  using namespace curio::hal::zynqmp;
  // Every pending interrupt in one entry; the IAR read that ends the loop answers 1023.
  for (bool any = false;; any = true) {
    const uint32_t iar = *cpu(kGiccIar);
    const uint32_t id = iar & 0x3FFu;
    if (id == kSpurious) {
      if (!any) ++g_counters.spurious;
      return;
    }
    if (id < kGicIds && g_slots[id].handler != nullptr) {
      ++g_counters.dispatched;
      g_slots[id].handler(g_slots[id].context);
    } else {
      ++g_counters.unhandled;
      Gic::disable(id);
    }
    *cpu(kGiccEoir) = iar;
  }
}
