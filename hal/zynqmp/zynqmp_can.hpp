// hal::CanBus on the ZynqMP's CAN controller (CAN 2.0B, two instances: CAN0 at 0xFF060000,
// CAN1 at 0xFF070000), register level, interrupt driven; written from Xilinx UG1085 ch. 20
// and the register reference UG1087. The chip-independent parts (bit timing, FIFO words,
// filters, error state) are in zynqmp_can_regs.hpp; docs/deploy.md describes the design and
// what a port to another controller (STM32H7 FDCAN) must do register by register.
//
//   Receive   the RXNEMP interrupt drains the 64-frame hardware RX FIFO into a software queue
//             of kRxQueueFrames (overrun: rx_dropped; a hardware RXOFLW counts too);
//             receive_batch pops it with the interrupt masked.
//   Transmit  send_batch queues frames with their deadline in a software TX queue of
//             kTxQueueFrames (full: kWouldBlock) and hands at most kTxWindow of them to the
//             hardware TX FIFO whenever it is empty (the TXFEMP interrupt, enabled only while
//             frames wait): a frame whose deadline passes while it waits in software is
//             dropped (tx_timedout), one handed over waits behind at most kTxWindow - 1 others.
//   Filters   up to 4 HAL filters of a given identifier width go into the acceptance filters
//             (AFMR/AFIR 1..4); more, or IdType::kAny ones, are applied in software to
//             what the hardware accepts (rx_filtered).
//   Errors    SR.ESTAT/ERRWRN are the HAL state; the BSOFF interrupt counts bus_off_events,
//             ERROR counts errors (ESR cleared); in bus-off sends are refused (kBusOff) and
//             the queued ones dropped; the controller leaves bus-off by itself after 128 × 11
//             recessive bits (CAN 2.0B), and restart() resets and reprograms it on demand.
//   Waiting   wait_readable sleeps in WFI until a frame's interrupt or the timeout (the
//             board's idle function, e.g. GenericTimer::idle_until).
// Firmware-clean: fixed queues, no heap, status codes and counters.
#pragma once
#include <cstddef>
#include <cstdint>

#include "hal/can_bus.hpp"
#include "hal/clock.hpp"
#include "hal/frame_queue.hpp"
#include "hal/zynqmp/zynqmp_can_regs.hpp"

namespace curio::hal::zynqmp {

inline constexpr uintptr_t kCan0Base = 0xFF060000u;
inline constexpr uintptr_t kCan1Base = 0xFF070000u;
// QEMU's model clocks the controllers at 24 MHz (XLNX_ZYNQMP_CAN_REF_CLK); a ZCU102 runs
// CAN_REF_CLK from a PLL, typically at 100 MHz.
inline constexpr uint32_t kQemuCanRefClockHz = 24'000'000u;

struct ZynqmpCanConfig {
  uintptr_t base = kCan0Base;
  uint32_t irq = 32 + 23;  // GIC ID (gic.hpp: kIrqCan0 / kIrqCan1)
  uint32_t ref_clock_hz = kQemuCanRefClockHz;
  uint32_t bitrate = 1'000'000;
  uint16_t sample_point_permille = 875;
  FrameWordLayout layout = FrameWordLayout::kUg1085;
  bool loopback = false;  // MSR.LBACK: frames return to this controller only, acknowledged
  // GIC priority of the controller's interrupt (lower is more urgent). Under QEMU the bus is
  // infinitely fast: a TX window leaves the moment it is written, so when both controllers of
  // one image talk to each other, the receiver's interrupt must outrank the sender's refill or
  // the receiver's 64-frame FIFO overflows (tests/zynqmp give CAN1 0x90, CAN0 0xA0).
  uint8_t irq_priority = 0xA0;
};

// The driver's own counters beside CanStats.
struct ZynqmpCanCounters {
  uint32_t interrupts = 0;
  uint32_t rx_hw_overflows = 0;   // RXOFLW: the hardware FIFO was full
  uint32_t rx_undecodable = 0;    // FIFO words no CAN 2.0B frame has
  uint32_t arbitration_lost = 0;  // ARBLST
  uint32_t error_interrupts = 0;  // ERROR
  uint32_t last_esr = 0;          // ESR at the last ERROR interrupt
  uint32_t tx_windows = 0;        // hand-overs to the hardware TX FIFO
  uint32_t restarts = 0;
};

enum class ZynqmpCanInit : uint8_t { kOk = 0, kBitTimingUnmet, kNoIrq };

class ZynqmpCan final : public CanBus {
 public:
  static constexpr size_t kRxQueueFrames = 256;
  static constexpr size_t kTxQueueFrames = 128;
  static constexpr size_t kTxWindow = 8;
  static_assert(kTxWindow <= kHwTxFifo, "the window fits the hardware TX FIFO");

  using IdleFn = void (*)(void* context, uint64_t until_us);

  // `idle(context, until)` sleeps until an interrupt or `until` on `clock` (called with IRQs
  // masked); null: wait_readable polls.
  ZynqmpCan(const Clock* clock, IdleFn idle = nullptr, void* idle_context = nullptr)
      : clock_(clock), idle_(idle), idle_context_(idle_context) {}

  // Resets the controller, programs bit timing (refused: kBitTimingUnmet, the controller stays
  // in configuration mode), attaches the interrupt (Gic::init() first) and joins the bus.
  ZynqmpCanInit init(const ZynqmpCanConfig& config);
  // Software reset and the same configuration again (filters kept): the explicit way out of
  // bus-off or a wedged controller. Queued TX frames are dropped (tx_timedout).
  void restart();

  CanStatus send_batch(const CanFrame* frames, size_t count, uint64_t deadline_us,
                       size_t* accepted) override;
  CanStatus receive_batch(CanFrame* out, size_t capacity, size_t* received) override;
  CanStatus wait_readable(uint64_t timeout_us) override;
  CanStatus set_filters(const CanFilter* filters, size_t count) override;
  CanStats stats() const override;
  BusState state() const override;
  bool carries_fd() const override { return false; }  // CAN 2.0B
  uint64_t now_us() const override { return clock_->now_us(); }

  const CanBitTiming& bit_timing() const { return timing_; }
  const ZynqmpCanCounters& counters() const { return counters_; }
  uint8_t tx_error_counter() const;
  uint8_t rx_error_counter() const;
  // Zeroes CanStats and the counters, empties the queues (test harnesses reuse a controller).
  void clear();

 private:
  struct TxEntry {
    CanFrame frame;
    uint64_t deadline_us = 0;
  };
  static void on_irq(void* self);
  void isr();
  void drain_rx_fifo();  // IRQs masked
  void feed_tx_fifo();   // IRQs masked
  void program();        // configuration mode: timing, mode, filters, interrupts
  void write_filters();
  void update_tx_irq();
  volatile uint32_t* reg(uint32_t offset) const {
    return reinterpret_cast<volatile uint32_t*>(config_.base + offset);
  }

  const Clock* clock_;
  IdleFn idle_;
  void* idle_context_;
  ZynqmpCanConfig config_;
  CanBitTiming timing_;
  RingQueue<CanFrame, kRxQueueFrames> rx_;
  RingQueue<TxEntry, kTxQueueFrames> tx_;
  CanFilter filters_[kMaxFilters] = {};
  size_t n_filters_ = 0;
  bool hw_filtering_ = true;  // all filters are in the acceptance filters
  CanStats stats_;
  ZynqmpCanCounters counters_;
  bool started_ = false;
};

}  // namespace curio::hal::zynqmp
