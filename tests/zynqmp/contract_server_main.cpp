// firmware.zynqmp.contract_server: serves hal::CanBus calls on the board's two CAN controllers
// to the host's bus contract test over UART0 (contract_rpc.hpp), so the same contract every
// backend passes (tests/hal/bus_contract.cpp) runs on this driver, on this image, under QEMU.
// It needs its peer on UART0 (run-zcu102.sh with ZCU102_SERIAL=unix:PATH): IMAGE_ONLY.
// The log goes to semihosting (QEMU's stderr); UART0 carries only the protocol.
#include <cstdint>
#include <cstring>

#include "hal/zynqmp/cadence_uart.hpp"
#include "hal/zynqmp/generic_timer.hpp"
#include "hal/zynqmp/gic.hpp"
#include "hal/zynqmp/zynqmp_can.hpp"
#include "tests/zynqmp/contract_rpc.hpp"
#include "toolchain/qemu/semihosting.h"

namespace {

using namespace curio;
using namespace curio::hal;
using namespace curio::hal::zynqmp;
using namespace curio::zynqmp_rpc;

GenericTimer g_timer;
CadenceUart g_uart;
void idle(void* timer, uint64_t until_us) {
  static_cast<GenericTimer*>(timer)->idle_until(until_us);
}
ZynqmpCan g_can[2] = {ZynqmpCan(&g_timer, &idle, &g_timer), ZynqmpCan(&g_timer, &idle, &g_timer)};
alignas(8) uint8_t g_in[kMaxPayload];
alignas(8) uint8_t g_out[kMaxPayload];

void read_bytes(void* dst, uint32_t n) {
  auto* p = static_cast<uint8_t*>(dst);
  for (uint32_t i = 0; i < n; ++i) {
    while (!g_uart.try_read(&p[i])) {
    }
  }
}

void write_bytes(const void* src, uint32_t n) {
  const auto* p = static_cast<const uint8_t*>(src);
  for (uint32_t i = 0; i < n; ++i) {
    while (!g_uart.try_write(p[i])) {
    }
  }
}

void reply(CanStatus status, uint32_t length) {
  ReplyHeader h;
  h.status = static_cast<uint8_t>(status);
  h.length = length;
  write_bytes(&h, sizeof h);
  write_bytes(g_out, length);
}

bool reset(FrameWordLayout layout) {
  for (int i = 0; i < 2; ++i) {
    ZynqmpCanConfig c;
    c.base = i == 0 ? kCan0Base : kCan1Base;
    c.irq = i == 0 ? kIrqCan0 : kIrqCan1;
    c.layout = layout;
    c.irq_priority = i == 0 ? 0xA0 : 0x90;  // the contract's bursts go CAN0 → CAN1
    if (g_can[i].init(c) != ZynqmpCanInit::kOk) return false;
    g_can[i].clear();
    g_can[i].set_filters(nullptr, 0);
  }
  return true;
}

template <typename T>
T take(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

int main() {
  g_uart.init();
  Gic::init();
  g_timer.init();
  irq_enable();
  if (!reset(FrameWordLayout::kUg1085)) {
    curio_semihost_print("contract server: CAN init failed\n");
    return 1;
  }
  curio_semihost_print("contract server: CAN0 + CAN1 ready, serving on UART0\n");
  write_bytes(&kReadyMagic, 1);
  uint32_t requests = 0;
  for (;;) {
    RequestHeader h;
    read_bytes(&h, sizeof h);
    if (h.magic != kRequestMagic || h.length > kMaxPayload || h.endpoint > 1) {
      curio_semihost_print("contract server: bad request header\n");
      return 2;
    }
    read_bytes(g_in, h.length);
    ++requests;
    ZynqmpCan& bus = g_can[h.endpoint];
    switch (h.op) {
      case Op::kReset:
        reply(reset(static_cast<FrameWordLayout>(g_in[0])) ? CanStatus::kOk : CanStatus::kIoError,
              0);
        break;
      case Op::kSend: {
        const auto deadline = take<uint64_t>(g_in);
        const auto count = take<uint32_t>(g_in + 8);
        if (count > kMaxFrames) return 2;
        CanFrame frames[kMaxFrames];
        std::memcpy(frames, g_in + 12, count * sizeof(CanFrame));
        size_t accepted = 0;
        const CanStatus s = bus.send_batch(frames, count, deadline, &accepted);
        const auto a = static_cast<uint32_t>(accepted);
        std::memcpy(g_out, &a, 4);
        reply(s, 4);
        break;
      }
      case Op::kReceive: {
        auto capacity = take<uint32_t>(g_in);
        if (capacity > kMaxFrames) capacity = kMaxFrames;
        CanFrame frames[kMaxFrames];
        size_t n = 0;
        const CanStatus s = bus.receive_batch(frames, capacity, &n);
        const auto n32 = static_cast<uint32_t>(n);
        std::memcpy(g_out, &n32, 4);
        std::memcpy(g_out + 4, frames, n * sizeof(CanFrame));
        reply(s, 4 + n32 * static_cast<uint32_t>(sizeof(CanFrame)));
        break;
      }
      case Op::kWait:
        reply(bus.wait_readable(take<uint64_t>(g_in)), 0);
        break;
      case Op::kFilters: {
        const auto count = take<uint32_t>(g_in);
        CanFilter filters[CanBus::kMaxFilters + 1];
        const uint32_t copy = count <= CanBus::kMaxFilters + 1 ? count : 0;
        std::memcpy(filters, g_in + 4, copy * sizeof(CanFilter));
        reply(copy == count ? bus.set_filters(filters, count) : CanStatus::kTooManyFilters, 0);
        break;
      }
      case Op::kStats: {
        const CanStats st = bus.stats();
        std::memcpy(g_out, &st, sizeof st);
        reply(CanStatus::kOk, sizeof st);
        break;
      }
      case Op::kState:
        g_out[0] = static_cast<uint8_t>(bus.state());
        reply(CanStatus::kOk, 1);
        break;
      case Op::kNow: {
        const uint64_t now = bus.now_us();
        std::memcpy(g_out, &now, 8);
        reply(CanStatus::kOk, 8);
        break;
      }
      case Op::kCarriesFd:
        g_out[0] = bus.carries_fd() ? 1 : 0;
        reply(CanStatus::kOk, 1);
        break;
      case Op::kExit:
        reply(CanStatus::kOk, 0);
        curio_semihost_print("contract server: ");
        curio_semihost_print_u32(requests);
        curio_semihost_print(" requests served; CAN0 interrupts ");
        curio_semihost_print_u32(g_can[0].counters().interrupts);
        curio_semihost_print(", CAN1 interrupts ");
        curio_semihost_print_u32(g_can[1].counters().interrupts);
        curio_semihost_print("\n");
        return 0;
      default:
        curio_semihost_print("contract server: unknown request\n");
        return 2;
    }
  }
}
