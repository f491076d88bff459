// SLCAN over a serial port as a hal::CanBus (slcan_bus.hpp).
#include "hal/slcan/slcan_bus.hpp"

namespace curio::hal {

SlcanBus::SlcanBus(SerialPort* port, const Clock* clock, protocol::SlcanMode mode)
    : port_(port), clock_(clock), assembler_(mode) {}

void SlcanBus::pump_rx() {
  uint8_t byte = 0;
  while (!rx_.full() && port_->try_read(&byte)) {
    ++rx_bytes_;
    CanFrame f;
    if (assembler_.push(byte, &f) != protocol::SlcanStatus::kFrame) continue;
    if (!filters_accept(filters_, n_filters_, f)) {
      ++stats_.rx_filtered;
      continue;
    }
    rx_.push(f);
  }
}

void SlcanBus::write_byte(uint8_t byte) {
  while (!port_->try_write(byte)) pump_rx();
  ++tx_bytes_;
}

CanStatus SlcanBus::send_batch(const CanFrame* frames, size_t count, uint64_t deadline_us,
                               size_t* accepted) {
  size_t n = 0;
  CanStatus status = CanStatus::kOk;
  for (; n < count; ++n) {
    const CanFrame& f = frames[n];
    if (!is_valid(f)) {
      status = CanStatus::kInvalidFrame;
      break;
    }
    char line[protocol::kSlcanMaxLine];
    const size_t len = protocol::slcan_encode(f, assembler_.mode(), line, sizeof line);
    if (len == 0) {  // error frame, or FD on a classic link
      status = CanStatus::kNotSupported;
      break;
    }
    if (clock_->now_us() > deadline_us) {
      if (n == 0) {
        ++stats_.tx_rejected;
        if (accepted != nullptr) *accepted = 0;
        return CanStatus::kDeadlineExpired;
      }
      ++stats_.tx_timedout;  // taken, but too late for the line
      continue;
    }
    for (size_t i = 0; i < len; ++i) write_byte(static_cast<uint8_t>(line[i]));
    ++stats_.tx_frames;
  }
  if (status != CanStatus::kOk) ++stats_.tx_rejected;
  if (accepted != nullptr) *accepted = n;
  return status;
}

CanStatus SlcanBus::receive_batch(CanFrame* out, size_t capacity, size_t* received) {
  pump_rx();
  size_t n = 0;
  while (n < capacity && rx_.pop(&out[n])) ++n;
  stats_.rx_frames += n;
  if (received != nullptr) *received = n;
  return n > 0 ? CanStatus::kOk : CanStatus::kEmpty;
}

CanStatus SlcanBus::wait_readable(uint64_t timeout_us) {
  const uint64_t start = clock_->now_us();
  for (;;) {
    pump_rx();
    if (!rx_.empty()) return CanStatus::kOk;
    if (clock_->now_us() - start >= timeout_us) return CanStatus::kTimeout;
  }
}

CanStatus SlcanBus::set_filters(const CanFilter* filters, size_t count) {
  if (count > kMaxFilters) return CanStatus::kTooManyFilters;
  for (size_t i = 0; i < count; ++i) filters_[i] = filters[i];
  n_filters_ = count;
  return CanStatus::kOk;
}

CanStats SlcanBus::stats() const {
  CanStats s = stats_;
  s.errors = assembler_.counters().malformed();
  return s;
}

}  // namespace curio::hal
