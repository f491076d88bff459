#include "hal/host/queued_bus.hpp"

#include <algorithm>

#include "hal/host/steady_clock.hpp"

namespace curio::hal {

QueuedBus::QueuedBus(const Clock* clock) : clock_(clock ? clock : &SteadyClock::instance()) {}

void QueuedBus::flush_backlog() {
  if (backlog_.empty()) return;  // the common case: no clock read, no syscall
  const uint64_t now = now_us();
  CanFrame chunk[kTxChunk];
  while (!backlog_.empty()) {
    if (now > backlog_.front().deadline_us) {
      backlog_.drop_front();
      ++stats_.tx_timedout;
      continue;
    }
    // The backlog is a ring: copy a run of live frames out, send them in one call.
    size_t n = 0;
    while (n < kTxChunk && n < backlog_.size() && now <= backlog_.at(n).deadline_us) {
      chunk[n] = backlog_.at(n).frame;
      ++n;
    }
    size_t sent = 0;
    const CanStatus s = transmit(chunk, n, &sent);
    stats_.tx_frames += sent;
    for (size_t i = 0; i < sent; ++i) backlog_.drop_front();
    if (s != CanStatus::kOk) return;
  }
}

CanStatus QueuedBus::send_batch(const CanFrame* frames, size_t count, uint64_t deadline_us,
                                size_t* accepted) {
  flush_backlog();
  size_t n = 0;
  CanStatus status = CanStatus::kOk;
  // The longest valid, supported prefix is what we try to send.
  size_t valid = 0;
  while (valid < count && is_valid(frames[valid]) && !frames[valid].error() &&
         supports(frames[valid])) {
    ++valid;
  }
  if (valid < count) {
    status = is_valid(frames[valid]) && !frames[valid].error() ? CanStatus::kNotSupported
                                                               : CanStatus::kInvalidFrame;
  }
  if (state_ == BusState::kBusOff || state_ == BusState::kDown) {
    valid = 0;
    status = state_ == BusState::kBusOff ? CanStatus::kBusOff : CanStatus::kIoError;
  } else if (valid > 0 && last_now_us_ > deadline_us) {
    ++stats_.tx_timedout;
    if (accepted) *accepted = 0;
    return CanStatus::kDeadlineExpired;
  }
  // Straight to the transport while nothing older waits (keeps the order).
  while (n < valid && backlog_.empty()) {
    const size_t chunk = std::min(kTxChunk, valid - n);
    size_t sent = 0;
    const CanStatus s = transmit(frames + n, chunk, &sent);
    stats_.tx_frames += sent;
    n += sent;
    if (s == CanStatus::kWouldBlock) break;
    if (s != CanStatus::kOk) {
      ++stats_.tx_rejected;
      if (accepted) *accepted = n;
      return s;
    }
  }
  for (; n < valid; ++n) {
    if (!backlog_.push({frames[n], deadline_us})) {
      status = CanStatus::kWouldBlock;
      break;
    }
  }
  if (status != CanStatus::kOk) ++stats_.tx_rejected;
  if (accepted) *accepted = n;
  return status;
}

}  // namespace curio::hal
