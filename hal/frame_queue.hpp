// Fixed-capacity FIFO of CAN frames (or any trivially copyable item): a static ring buffer,
// Zephyr-style message queue without locking. Firmware-clean.
#pragma once
#include <cstddef>

#include "hal/can_frame.hpp"

namespace curio::hal {

template <typename T, size_t N>
class RingQueue {
  static_assert(N > 0, "queue needs room");

 public:
  static constexpr size_t kCapacity = N;

  bool push(const T& item) {
    if (size_ == N) return false;
    items_[(head_ + size_) % N] = item;
    ++size_;
    return true;
  }
  bool pop(T* out) {
    if (size_ == 0) return false;
    *out = items_[head_];
    head_ = (head_ + 1) % N;
    --size_;
    return true;
  }
  const T& front() const { return items_[head_]; }
  // i-th item from the front (i < size()).
  const T& at(size_t i) const { return items_[(head_ + i) % N]; }
  void drop_front() {
    if (size_ == 0) return;
    head_ = (head_ + 1) % N;
    --size_;
  }
  void clear() { head_ = size_ = 0; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == N; }

 private:
  T items_[N] = {};
  size_t head_ = 0;
  size_t size_ = 0;
};

template <size_t N>
using FrameQueue = RingQueue<CanFrame, N>;

// A frame waiting for the bus and the time after which it is worthless.
struct PendingFrame {
  CanFrame frame;
  uint64_t deadline_us = 0;
};

}  // namespace curio::hal
