// The ZynqMP CAN controller behind hal::CanBus (zynqmp_can.hpp).
#include "hal/zynqmp/zynqmp_can.hpp"

#include "hal/zynqmp/gic.hpp"

namespace curio::hal::zynqmp {

using namespace can_reg;

namespace {
constexpr uint32_t kIrqAll = 0x7FFFu;
constexpr uint32_t kIrqAlwaysOn = kIrqRxNemp | kIrqRxOflw | kIrqError | kIrqBsOff | kIrqArbLst;
constexpr int kAcfBusySpins = 1000;
}  // namespace

ZynqmpCanInit ZynqmpCan::init(const ZynqmpCanConfig& config) {
  config_ = config;
  started_ = false;
  *reg(kSrr) = kSrrSrst;  // reset: configuration mode
  if (!compute_bit_timing(config.ref_clock_hz, config.bitrate, config.sample_point_permille,
                          &timing_)) {
    return ZynqmpCanInit::kBitTimingUnmet;
  }
  if (!Gic::attach(config.irq, &ZynqmpCan::on_irq, this, config.irq_priority))
    return ZynqmpCanInit::kNoIrq;
  IrqLock lock;
  program();
  return ZynqmpCanInit::kOk;
}

void ZynqmpCan::program() {
  *reg(kSrr) = kSrrSrst;  // every register back to reset, configuration mode
  *reg(kBrpr) = timing_.brpr_value();
  *reg(kBtr) = timing_.btr_value();
  *reg(kMsr) = config_.loopback ? kMsrLback : 0u;
  write_filters();
  // Every stale status cleared but TXFEMP: the reset leaves it set (the FIFO is empty) and it
  // is only set again on the next transition to empty.
  *reg(kIcr) = kIrqAll & ~kIrqTxFemp;
  *reg(kIer) = kIrqAlwaysOn;
  *reg(kSrr) = kSrrCen;  // join the bus (normal or loopback mode)
  started_ = true;
}

void ZynqmpCan::restart() {
  IrqLock lock;
  stats_.tx_timedout += tx_.size();
  tx_.clear();
  ++counters_.restarts;
  program();
}

void ZynqmpCan::on_irq(void* self) {
  static_cast<ZynqmpCan*>(self)->isr();
}

void ZynqmpCan::isr() {
  ++counters_.interrupts;
  const uint32_t pending = *reg(kIsr) & *reg(kIer);
  if ((pending & kIrqRxNemp) != 0) drain_rx_fifo();
  if ((pending & kIrqRxOflw) != 0) {
    ++counters_.rx_hw_overflows;
    ++stats_.rx_dropped;
  }
  if ((pending & kIrqArbLst) != 0) ++counters_.arbitration_lost;
  if ((pending & kIrqError) != 0) {
    const uint32_t esr = *reg(kEsr);
    *reg(kEsr) = esr;  // write 1 to clear
    counters_.last_esr = esr;
    ++counters_.error_interrupts;
    ++stats_.errors;
  }
  if ((pending & kIrqBsOff) != 0) {
    ++stats_.bus_off_events;
    stats_.tx_timedout += tx_.size();  // they cannot reach the bus in time
    tx_.clear();
  }
  *reg(kIcr) = pending & ~(kIrqRxNemp | kIrqTxFemp);
  if ((pending & kIrqTxFemp) != 0) feed_tx_fifo();
}

void ZynqmpCan::drain_rx_fifo() {
  // Each frame: four word reads, then RXNEMP cleared; the controller sets it again while
  // frames remain. Bounded by the FIFO's depth (a misbehaving controller cannot hang us).
  for (size_t i = 0; i <= kHwRxFifo && (*reg(kIsr) & kIrqRxNemp) != 0; ++i) {
    FrameWords w;
    w.id = *reg(kRxFifoId);
    w.dlc = *reg(kRxFifoId + 4);
    w.dw1 = *reg(kRxFifoId + 8);
    w.dw2 = *reg(kRxFifoId + 12);
    *reg(kIcr) = kIrqRxNemp | kIrqRxOk;
    CanFrame f;
    if (!decode_frame(w, config_.layout, &f)) {
      ++counters_.rx_undecodable;
      ++stats_.errors;
      continue;
    }
    if (!hw_filtering_ && !filters_accept(filters_, n_filters_, f)) {
      ++stats_.rx_filtered;
      continue;
    }
    if (!rx_.push(f)) ++stats_.rx_dropped;
  }
}

void ZynqmpCan::feed_tx_fifo() {
  // A new window only when the hardware FIFO is empty (TXFEMP), so a frame handed over
  // waits behind at most kTxWindow - 1 others. TXFEMP is cleared before the first write: it
  // is set again when this window has left.
  if ((*reg(kIsr) & kIrqTxFemp) == 0) {
    update_tx_irq();
    return;
  }
  const uint64_t now = clock_->now_us();
  size_t handed = 0;
  while (!tx_.empty() && handed < kTxWindow && (*reg(kSr) & kSrTxFll) == 0) {
    const TxEntry& e = tx_.front();
    if (now > e.deadline_us) {
      ++stats_.tx_timedout;
      tx_.drop_front();
      continue;
    }
    FrameWords w;
    if (!encode_frame(e.frame, config_.layout, &w)) {  // validated in send_batch
      ++stats_.tx_rejected;
      tx_.drop_front();
      continue;
    }
    if (handed == 0) *reg(kIcr) = kIrqTxFemp;
    *reg(kTxFifoId) = w.id;
    *reg(kTxFifoId + 4) = w.dlc;
    *reg(kTxFifoId + 8) = w.dw1;
    *reg(kTxFifoId + 12) = w.dw2;  // queues the frame
    ++stats_.tx_frames;
    ++handed;
    tx_.drop_front();
  }
  if (handed > 0) ++counters_.tx_windows;
  update_tx_irq();
}

void ZynqmpCan::update_tx_irq() {
  // TXFEMP is a level: enabled only while frames wait, or it would fire on an idle FIFO.
  *reg(kIer) = tx_.empty() ? kIrqAlwaysOn : (kIrqAlwaysOn | kIrqTxFemp);
}

CanStatus ZynqmpCan::send_batch(const CanFrame* frames, size_t count, uint64_t deadline_us,
                                size_t* accepted) {
  size_t n = 0;
  CanStatus status = CanStatus::kOk;
  {
    IrqLock lock;
    const bool expired = clock_->now_us() > deadline_us;
    for (; n < count; ++n) {
      const CanFrame& f = frames[n];
      if (!is_valid(f)) {
        status = CanStatus::kInvalidFrame;
      } else if (f.fd() || f.error()) {
        status = CanStatus::kNotSupported;
      } else if (state() == BusState::kBusOff || !started_) {
        status = CanStatus::kBusOff;
      } else if (expired) {
        ++stats_.tx_timedout;
        status = CanStatus::kDeadlineExpired;
        break;
      } else if (!tx_.push(TxEntry{f, deadline_us})) {
        status = CanStatus::kWouldBlock;
      }
      if (status != CanStatus::kOk) {
        ++stats_.tx_rejected;
        break;
      }
    }
    feed_tx_fifo();
  }
  if (accepted != nullptr) *accepted = n;
  return status;
}

CanStatus ZynqmpCan::receive_batch(CanFrame* out, size_t capacity, size_t* received) {
  size_t n = 0;
  {
    IrqLock lock;
    while (n < capacity && rx_.pop(&out[n])) ++n;
    stats_.rx_frames += n;
  }
  if (received != nullptr) *received = n;
  return n > 0 ? CanStatus::kOk : CanStatus::kEmpty;
}

CanStatus ZynqmpCan::wait_readable(uint64_t timeout_us) {
  const uint64_t until = clock_->now_us() + timeout_us;
  IrqLock lock;
  for (;;) {
    if (!rx_.empty()) return CanStatus::kOk;
    if (clock_->now_us() >= until) return CanStatus::kTimeout;
    if (idle_ != nullptr) {
      idle_(idle_context_, until);
    } else {
      irq_enable();  // let a pending interrupt in, then look again
      irq_disable();
    }
  }
}

CanStatus ZynqmpCan::set_filters(const CanFilter* filters, size_t count) {
  if (count > kMaxFilters) return CanStatus::kTooManyFilters;
  IrqLock lock;
  for (size_t i = 0; i < count; ++i) filters_[i] = filters[i];
  n_filters_ = count;
  if (started_) write_filters();
  return CanStatus::kOk;
}

void ZynqmpCan::write_filters() {
  // UG1085: a filter's mask and ID are written with its UAF bit 0, after ACFBSY clears.
  *reg(kAfr) = 0;  // no filter enabled: every frame is accepted
  uint32_t masks[kHwFilters] = {}, ids[kHwFilters] = {};
  hw_filtering_ = n_filters_ <= kHwFilters;
  for (size_t i = 0; i < n_filters_ && hw_filtering_; ++i) {
    hw_filtering_ = encode_filter(filters_[i], config_.layout, &masks[i], &ids[i]);
  }
  if (!hw_filtering_ || n_filters_ == 0) return;
  for (int spin = 0; spin < kAcfBusySpins && (*reg(kSr) & kSrAcfBsy) != 0; ++spin) {
  }
  for (size_t i = 0; i < n_filters_; ++i) {
    *reg(kAfmr1 + 8 * static_cast<uint32_t>(i)) = masks[i];
    *reg(kAfir1 + 8 * static_cast<uint32_t>(i)) = ids[i];
  }
  *reg(kAfr) = (1u << n_filters_) - 1u;
}

CanStats ZynqmpCan::stats() const {
  IrqLock lock;
  return stats_;
}

BusState ZynqmpCan::state() const {
  if (!started_) return BusState::kDown;
  return bus_state_from(*reg(kSr));
}

uint8_t ZynqmpCan::tx_error_counter() const {
  return static_cast<uint8_t>(*reg(kEcr));
}
uint8_t ZynqmpCan::rx_error_counter() const {
  return static_cast<uint8_t>(*reg(kEcr) >> 8);
}

void ZynqmpCan::clear() {
  IrqLock lock;
  rx_.clear();
  tx_.clear();
  stats_ = CanStats{};
  counters_ = ZynqmpCanCounters{};
}

}  // namespace curio::hal::zynqmp
