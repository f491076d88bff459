// hal::CanBus over a serial line carrying SLCAN (firmware/protocol/slcan.hpp): the bus
// backend of a board whose CAN link is a UART (the QEMU image's UART0 to curio-can
// slcan-bridge, or a USB-CAN adapter's serial side). Polled, fixed queues, no heap, no OS.
//
// Transmit: each frame becomes one line, written byte by byte as the port takes them (the
// receive side is drained meanwhile, so two ends that both block on a full line cannot
// deadlock). A frame whose deadline has passed before its first byte is dropped and counted
// (tx_timedout); a line once begun is finished (a half line would corrupt the next one).
// Receive: bytes are read only while the receive queue has room, so a flow-controlled
// transport (QEMU's chardev, a socket) holds back what we cannot store instead of losing it.
// Malformed lines are counted in stats().errors (details in slcan_counters()).
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/protocol/slcan.hpp"
#include "hal/can_bus.hpp"
#include "hal/clock.hpp"
#include "hal/frame_queue.hpp"
#include "hal/serial_port.hpp"

namespace curio::hal {

class SlcanBus final : public CanBus {
 public:
  static constexpr size_t kRxQueueFrames = 64;

  SlcanBus(SerialPort* port, const Clock* clock, protocol::SlcanMode mode);

  CanStatus send_batch(const CanFrame* frames, size_t count, uint64_t deadline_us,
                       size_t* accepted) override;
  CanStatus receive_batch(CanFrame* out, size_t capacity, size_t* received) override;
  CanStatus wait_readable(uint64_t timeout_us) override;
  CanStatus set_filters(const CanFilter* filters, size_t count) override;
  CanStats stats() const override;
  BusState state() const override { return BusState::kErrorActive; }
  // An FD link (the d/D/b/B lines between Curio's own endpoints) or a classic one.
  bool carries_fd() const override { return assembler_.mode() == protocol::SlcanMode::kFd; }
  uint64_t now_us() const override { return clock_->now_us(); }

  const protocol::SlcanCounters& slcan_counters() const { return assembler_.counters(); }
  // Bytes written and read on the serial line (rates in docs/can.md).
  uint64_t tx_bytes() const { return tx_bytes_; }
  uint64_t rx_bytes() const { return rx_bytes_; }

 private:
  // Reads what the port has, while the receive queue has room.
  void pump_rx();
  void write_byte(uint8_t byte);

  SerialPort* port_;
  const Clock* clock_;
  protocol::SlcanLineAssembler assembler_;
  FrameQueue<kRxQueueFrames> rx_;
  CanFilter filters_[kMaxFilters] = {};
  size_t n_filters_ = 0;
  CanStats stats_;
  uint64_t tx_bytes_ = 0;
  uint64_t rx_bytes_ = 0;
};

}  // namespace curio::hal
