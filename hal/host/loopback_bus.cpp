#include "hal/host/loopback_bus.hpp"

#include <chrono>
#include <map>

#include "hal/host/steady_clock.hpp"

namespace curio::hal {

std::shared_ptr<LoopbackBus> LoopbackBus::create(const Clock* clock) {
  return std::shared_ptr<LoopbackBus>(new LoopbackBus(clock ? clock : &SteadyClock::instance()));
}

std::unique_ptr<LoopbackEndpoint> LoopbackBus::open(bool carries_fd) {
  std::lock_guard lock(mutex_);
  for (size_t i = 0; i < kMaxEndpoints; ++i) {
    if (endpoints_[i] == nullptr) {
      std::unique_ptr<LoopbackEndpoint> ep(
          new LoopbackEndpoint(shared_from_this(), i, carries_fd));
      endpoints_[i] = ep.get();
      return ep;
    }
  }
  return nullptr;
}

size_t LoopbackBus::endpoint_count() const {
  std::lock_guard lock(mutex_);
  size_t n = 0;
  for (auto* ep : endpoints_) n += ep != nullptr ? 1 : 0;
  return n;
}

void LoopbackBus::set_tx_paused(bool paused) {
  std::lock_guard lock(mutex_);
  paused_ = paused;
  if (!paused_) flush_pending_locked();
}

void LoopbackBus::deliver_locked(size_t sender, const CanFrame& frame) {
  LoopbackEndpoint* from = endpoints_[sender];
  if (from != nullptr) ++from->stats_.tx_frames;
  for (size_t i = 0; i < kMaxEndpoints; ++i) {
    LoopbackEndpoint* to = endpoints_[i];
    // A node that is bus-off or down is not on the bus: it hears nothing.
    if (to == nullptr || i == sender || to->state_ == BusState::kDown ||
        to->state_ == BusState::kBusOff) {
      continue;
    }
    if (frame.fd() && !to->carries_fd_) {
      ++to->stats_.errors;  // a classic controller cannot read an FD frame
    } else if (!filters_accept(to->filters_, to->filter_count_, frame)) {
      ++to->stats_.rx_filtered;
    } else if (!to->rx_.push(frame)) {
      ++to->stats_.rx_dropped;
    }
  }
  readable_.notify_all();
}

void LoopbackBus::flush_pending_locked() {
  const uint64_t now = clock_->now_us();
  Pending p;
  while (pending_.pop(&p)) {
    LoopbackEndpoint* from = endpoints_[p.sender];
    if (from == nullptr) continue;  // sender closed meanwhile
    if (now > p.deadline_us) {
      ++from->stats_.tx_timedout;
      continue;
    }
    deliver_locked(p.sender, p.frame);
  }
}

LoopbackEndpoint::~LoopbackEndpoint() {
  std::lock_guard lock(bus_->mutex_);
  // Frames this node queued while paused die with it, before its slot can be reused.
  const size_t n = bus_->pending_.size();
  for (size_t i = 0; i < n; ++i) {
    LoopbackBus::Pending p;
    bus_->pending_.pop(&p);
    if (p.sender != index_) bus_->pending_.push(p);
  }
  bus_->endpoints_[index_] = nullptr;
}

CanStatus LoopbackEndpoint::send_batch(const CanFrame* frames, size_t count, uint64_t deadline_us,
                                       size_t* accepted) {
  std::lock_guard lock(bus_->mutex_);
  size_t n = 0;
  CanStatus status = CanStatus::kOk;
  const uint64_t now = bus_->clock_->now_us();
  for (; n < count; ++n) {
    const CanFrame& f = frames[n];
    if (state_ == BusState::kBusOff || state_ == BusState::kDown) {
      status = state_ == BusState::kBusOff ? CanStatus::kBusOff : CanStatus::kIoError;
    } else if (!is_valid(f) || f.error()) {
      status = CanStatus::kInvalidFrame;
    } else if (f.fd() && !carries_fd_) {
      status = CanStatus::kNotSupported;
    } else if (now > deadline_us) {
      ++stats_.tx_timedout;
      status = CanStatus::kDeadlineExpired;
      break;
    } else if (bus_->paused_) {
      if (!bus_->pending_.push({f, deadline_us, index_})) status = CanStatus::kWouldBlock;
    } else {
      bus_->deliver_locked(index_, f);
    }
    if (status != CanStatus::kOk) {
      ++stats_.tx_rejected;
      break;
    }
  }
  if (accepted) *accepted = n;
  return status;
}

CanStatus LoopbackEndpoint::receive_batch(CanFrame* out, size_t capacity, size_t* received) {
  std::lock_guard lock(bus_->mutex_);
  size_t n = 0;
  while (n < capacity && rx_.pop(&out[n])) ++n;
  stats_.rx_frames += n;
  if (received) *received = n;
  return n > 0 ? CanStatus::kOk : CanStatus::kEmpty;
}

CanStatus LoopbackEndpoint::wait_readable(uint64_t timeout_us) {
  std::unique_lock lock(bus_->mutex_);
  const bool ready = bus_->readable_.wait_for(lock, std::chrono::microseconds(timeout_us),
                                              [this] { return !rx_.empty(); });
  return ready ? CanStatus::kOk : CanStatus::kTimeout;
}

CanStatus LoopbackEndpoint::set_filters(const CanFilter* filters, size_t count) {
  if (count > kMaxFilters) return CanStatus::kTooManyFilters;
  std::lock_guard lock(bus_->mutex_);
  for (size_t i = 0; i < count; ++i) filters_[i] = filters[i];
  filter_count_ = count;
  return CanStatus::kOk;
}

CanStats LoopbackEndpoint::stats() const {
  std::lock_guard lock(bus_->mutex_);
  return stats_;
}

BusState LoopbackEndpoint::state() const {
  std::lock_guard lock(bus_->mutex_);
  return state_;
}

uint64_t LoopbackEndpoint::now_us() const {
  return bus_->clock_->now_us();
}

void LoopbackEndpoint::force_state(BusState state) {
  std::lock_guard lock(bus_->mutex_);
  if (state == BusState::kBusOff && state_ != BusState::kBusOff) ++stats_.bus_off_events;
  state_ = state;
}

std::shared_ptr<LoopbackBus> named_loopback_bus(const std::string& name, const Clock* clock) {
  static std::mutex registry_mutex;
  static std::map<std::string, std::weak_ptr<LoopbackBus>> registry;
  std::lock_guard lock(registry_mutex);
  if (auto bus = registry[name].lock()) return bus;
  auto bus = LoopbackBus::create(clock);
  registry[name] = bus;
  return bus;
}

}  // namespace curio::hal
