// firmware.zynqmp.board: the ZynqMP board port and its CAN driver on QEMU's xlnx-zcu102, CAN0
// and CAN1 on one QEMU CAN bus. Checks: the core runs AArch32 Secure SVC after the boot stub;
// the generic timer counts and its alarm wakes the core from WFI through the GIC; both
// controllers' frames cross the bus interrupt-driven (every length, both identifier widths,
// remote requests, a 200-frame burst in order), in the chip's frame-word layout and in QEMU's;
// acceptance filters in hardware and in software; deadlines, FD refusal, invalid frames;
// loopback mode; bit timing computed and an unmeetable bitrate refused; the error state.
// Returns the number of failed checks (QEMU's exit status).
#include <cstdint>

#include "hal/zynqmp/generic_timer.hpp"
#include "hal/zynqmp/gic.hpp"
#include "hal/zynqmp/zynqmp_can.hpp"
#include "tests/zynqmp/board_test_util.hpp"

namespace {

using namespace curio;
using namespace curio::hal;
using namespace curio::hal::zynqmp;
using zynqmp_test::print;
using zynqmp_test::print_u32;

GenericTimer g_timer;

void idle(void* timer, uint64_t until_us) {
  static_cast<GenericTimer*>(timer)->idle_until(until_us);
}

ZynqmpCan g_can0(&g_timer, &idle, &g_timer);
ZynqmpCan g_can1(&g_timer, &idle, &g_timer);

CanFrame frame(uint32_t id, uint8_t len, bool extended = false, uint8_t seed = 0) {
  CanFrame f;
  f.id = id;
  f.len = len;
  f.flags = extended ? kFlagExtended : 0;
  for (uint8_t i = 0; i < len; ++i) f.data[i] = static_cast<uint8_t>(seed * 7u + i * 31u + 1u);
  return f;
}

bool same(const CanFrame& a, const CanFrame& b) {
  if (a.id != b.id || a.len != b.len || a.flags != b.flags) return false;
  if (a.remote()) return true;
  for (uint8_t i = 0; i < a.len; ++i) {
    if (a.data[i] != b.data[i]) return false;
  }
  return true;
}

uint64_t soon() {
  return g_timer.now_us() + 1'000'000;
}

ZynqmpCanConfig config(int which, FrameWordLayout layout, bool loopback = false) {
  ZynqmpCanConfig c;
  c.base = which == 0 ? kCan0Base : kCan1Base;
  c.irq = which == 0 ? kIrqCan0 : kIrqCan1;
  c.layout = layout;
  c.loopback = loopback;
  c.irq_priority = which == 0 ? 0xA0 : 0x90;  // the receiver of the bursts outranks the sender
  return c;
}

// Frames of every classic length and both widths, and remote requests, from a to b.
void round_trips(ZynqmpCan& a, ZynqmpCan& b) {
  CanFrame sent[20];
  size_t n = 0;
  for (uint8_t len = 0; len <= 8; ++len) {
    sent[n++] = frame(0x18DAF120u + len, len, true, len);
    sent[n++] = frame(0x7FFu - len, len, false, len);
  }
  sent[n] = frame(0x321, 4);
  sent[n++].flags = kFlagRemote;
  sent[n] = frame(0x1ABCDEF0u, 2, true);
  sent[n++].flags = kFlagExtended | kFlagRemote;
  size_t accepted = 0;
  ZCHECK(a.send_batch(sent, n, soon(), &accepted) == CanStatus::kOk && accepted == n);
  for (size_t i = 0; i < n; ++i) {
    CanFrame got;
    const bool ok = b.receive(&got, 200'000) == CanStatus::kOk;
    ZCHECK(ok && same(got, sent[i]));
  }
  CanFrame none;
  ZCHECK(a.receive(&none) == CanStatus::kEmpty);  // a sender does not hear itself
}

}  // namespace

int main() {
  zynqmp_test::g_console.init();
  print("zcu102 board test: Cortex-A53 in AArch32, GICv2, generic timer, CAN0 + CAN1\n");
  uint32_t cpsr = 0;
  __asm__ volatile("mrs %0, cpsr" : "=r"(cpsr));
  ZCHECK((cpsr & 0x1Fu) == 0x13u);  // SVC mode, AArch32
  Gic::init();
  g_timer.init();
  irq_enable();
  ZCHECK(g_timer.frequency_hz() > 0);

  // The alarm wakes WFI.
  const uint64_t t0 = g_timer.now_us();
  {
    IrqLock lock;
    g_timer.idle_until(t0 + 5'000);
  }
  const uint64_t t1 = g_timer.now_us();
  ZCHECK(t1 - t0 >= 5'000 && g_timer.alarms() >= 1);
  print("  timer ");
  print_u32(g_timer.frequency_hz());
  print(" Hz; a 5 ms idle took ");
  print_u32(t1 - t0);
  print(" us\n");

  // Bit timing: 1 Mbit/s from QEMU's 24 MHz: 8 quanta of 125 ns, sampled at 87.5 %.
  ZCHECK(g_can0.init(config(0, FrameWordLayout::kUg1085)) == ZynqmpCanInit::kOk);
  ZCHECK(g_can1.init(config(1, FrameWordLayout::kUg1085)) == ZynqmpCanInit::kOk);
  const CanBitTiming& bt = g_can0.bit_timing();
  ZCHECK(bt.brp == 3 && bt.ts1 == 6 && bt.ts2 == 1 && bt.sample_point_permille == 875);
  ZCHECK(g_can0.state() == BusState::kErrorActive && g_can1.state() == BusState::kErrorActive);
  ZCHECK(g_can0.tx_error_counter() == 0 && g_can0.rx_error_counter() == 0);
  ZCHECK(!g_can0.carries_fd());

  // Silence: wait_readable sleeps until its timeout.
  const uint64_t w0 = g_timer.now_us();
  ZCHECK(g_can1.wait_readable(20'000) == CanStatus::kTimeout);
  ZCHECK(g_timer.now_us() - w0 >= 20'000);

  round_trips(g_can0, g_can1);
  round_trips(g_can1, g_can0);

  // A burst larger than both hardware FIFOs, in order.
  static CanFrame burst[200];
  for (size_t i = 0; i < 200; ++i) burst[i] = frame(0x200, 8, false, static_cast<uint8_t>(i));
  ZCHECK(send_all(g_can0, burst, 200, soon()) == CanStatus::kOk);
  size_t in_order = 0;
  for (size_t i = 0; i < 200; ++i) {
    CanFrame got;
    if (g_can1.receive(&got, 200'000) == CanStatus::kOk && same(got, burst[i])) ++in_order;
  }
  ZCHECK(in_order == 200);
  print("  burst: ");
  print_u32(in_order);
  print(" of 200 frames in order; CAN1 interrupts ");
  print_u32(g_can1.counters().interrupts);
  print(", CAN0 TX windows ");
  print_u32(g_can0.counters().tx_windows);
  print("\n");
  ZCHECK(g_can1.counters().interrupts > 0 &&
         g_can0.counters().tx_windows >= 200 / ZynqmpCan::kTxWindow);

  // Acceptance filters: two in hardware; an IdType::kAny one in software.
  const CanFilter hw[] = {{0x120, 0x7F0, IdType::kStandard},
                          {0x18DAF120u, 0x1FFFFFFFu, IdType::kExtended}};
  ZCHECK(g_can1.set_filters(hw, 2) == CanStatus::kOk);
  const CanFrame mixed[] = {frame(0x121, 1),
                            frame(0x131, 1),
                            frame(0x12F, 2),
                            frame(0x121, 1, true),
                            frame(0x18DAF120u, 8, true),
                            frame(0x18DAF121u, 8, true)};
  ZCHECK(g_can0.send_batch(mixed, 6, soon(), nullptr) == CanStatus::kOk);
  const uint32_t want[] = {0x121, 0x12F, 0x18DAF120u};
  for (uint32_t id : want) {
    CanFrame got;
    ZCHECK(g_can1.receive(&got, 200'000) == CanStatus::kOk && got.id == id);
  }
  CanFrame none;
  ZCHECK(g_can1.receive(&none, 20'000) == CanStatus::kTimeout);
  ZCHECK(g_can1.stats().rx_filtered == 0);  // the hardware filtered them
  const CanFilter any[] = {{0x123, 0x7FF, IdType::kAny}};
  ZCHECK(g_can1.set_filters(any, 1) == CanStatus::kOk);
  ZCHECK(g_can0.send(frame(0x124, 1), soon()) == CanStatus::kOk);
  ZCHECK(g_can0.send(frame(0x123, 1), soon()) == CanStatus::kOk);
  ZCHECK(g_can1.receive(&none, 200'000) == CanStatus::kOk && none.id == 0x123);
  ZCHECK(g_can1.stats().rx_filtered == 1);  // the software filtered it
  CanFilter many[CanBus::kMaxFilters + 1] = {};
  ZCHECK(g_can1.set_filters(many, CanBus::kMaxFilters + 1) == CanStatus::kTooManyFilters);
  ZCHECK(g_can1.set_filters(nullptr, 0) == CanStatus::kOk);

  // Refusals: expired deadline, FD, invalid.
  const CanStats before = g_can0.stats();
  ZCHECK(g_can0.send(frame(0x100, 8), g_timer.now_us() - 1) == CanStatus::kDeadlineExpired);
  CanFrame fd = frame(0x100, 8);
  fd.flags = kFlagFd;
  ZCHECK(g_can0.send(fd, soon()) == CanStatus::kNotSupported);
  CanFrame bad = frame(0x800, 1);
  ZCHECK(g_can0.send(bad, soon()) == CanStatus::kInvalidFrame);
  ZCHECK(g_can0.stats().tx_timedout == before.tx_timedout + 1);
  ZCHECK(g_can0.stats().tx_rejected == before.tx_rejected + 2);
  ZCHECK(g_can1.receive(&none, 20'000) == CanStatus::kTimeout);

  // QEMU's frame-word layout (the one that reaches Linux through can-host-socketcan).
  ZCHECK(g_can0.init(config(0, FrameWordLayout::kQemu72)) == ZynqmpCanInit::kOk);
  ZCHECK(g_can1.init(config(1, FrameWordLayout::kQemu72)) == ZynqmpCanInit::kOk);
  round_trips(g_can0, g_can1);
  ZCHECK(g_can1.set_filters(hw, 2) == CanStatus::kOk);
  ZCHECK(g_can0.send_batch(mixed, 6, soon(), nullptr) == CanStatus::kOk);
  for (uint32_t id : want) {
    CanFrame got;
    ZCHECK(g_can1.receive(&got, 200'000) == CanStatus::kOk && got.id == id);
  }
  ZCHECK(g_can1.receive(&none, 20'000) == CanStatus::kTimeout);
  ZCHECK(g_can1.set_filters(nullptr, 0) == CanStatus::kOk);

  // Loopback mode: CAN0 hears its own frames, acknowledged, and the bus hears nothing.
  ZCHECK(g_can0.init(config(0, FrameWordLayout::kUg1085, true)) == ZynqmpCanInit::kOk);
  ZCHECK(g_can1.init(config(1, FrameWordLayout::kUg1085)) == ZynqmpCanInit::kOk);
  const CanFrame echo = frame(0x456, 3);
  ZCHECK(g_can0.send(echo, soon()) == CanStatus::kOk);
  ZCHECK(g_can0.receive(&none, 200'000) == CanStatus::kOk && same(none, echo));
  ZCHECK(g_can1.receive(&none, 20'000) == CanStatus::kTimeout);

  // A bitrate the 24 MHz clock cannot divide into 8..25 quanta is refused; the controller
  // stays off the bus.
  ZynqmpCanConfig odd = config(0, FrameWordLayout::kUg1085);
  odd.bitrate = 999'999;
  ZCHECK(g_can0.init(odd) == ZynqmpCanInit::kBitTimingUnmet);
  ZCHECK(g_can0.state() == BusState::kDown);
  ZCHECK(g_can0.send(echo, soon()) == CanStatus::kBusOff);
  // restart() after a good init: back on the bus.
  ZCHECK(g_can0.init(config(0, FrameWordLayout::kUg1085)) == ZynqmpCanInit::kOk);
  g_can0.restart();
  ZCHECK(g_can0.state() == BusState::kErrorActive && g_can0.counters().restarts == 1);
  ZCHECK(g_can0.send(echo, soon()) == CanStatus::kOk);
  ZCHECK(g_can1.receive(&none, 200'000) == CanStatus::kOk && same(none, echo));

  print("  GIC: ");
  print_u32(Gic::counters().dispatched);
  print(" interrupts dispatched, ");
  print_u32(Gic::counters().spurious);
  print(" spurious, ");
  print_u32(Gic::counters().unhandled);
  print(" unhandled\n");
  ZCHECK(Gic::counters().unhandled == 0);
  print(zynqmp_test::g_failures == 0 ? "PASS\n" : "FAILED\n");
  return static_cast<int>(zynqmp_test::g_failures);
}
