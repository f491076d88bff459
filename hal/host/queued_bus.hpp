// Shared TX logic of the socket backends (SocketCAN, UDP): frames the transport cannot take
// right now (EAGAIN/ENOBUFS) wait in a fixed backlog and are retried on every later call;
// those whose deadline passes first are dropped and counted (ArduPilot's Linux CAN driver
// does the same). Derived classes implement only transmit() and receive.
// Deadline check of a frame the transport takes at once: against the latest clock reading
// (now_us() calls, backlog flushes), so a deadline computed as now_us() + X is never judged
// on a stale clock in the caller's favour by more than the time since that call.
#pragma once
#include "hal/can_bus.hpp"
#include "hal/clock.hpp"
#include "hal/frame_queue.hpp"

namespace curio::hal {

class QueuedBus : public CanBus {
 public:
  static constexpr size_t kBacklogDepth = 512;
  static constexpr size_t kTxChunk = 64;  // frames per transmit() call (one syscall)

  CanStatus send_batch(const CanFrame* frames, size_t count, uint64_t deadline_us,
                       size_t* accepted) override;
  CanStats stats() const override { return stats_; }
  BusState state() const override { return state_; }
  // Also remembered: deadlines of frames handed straight to the transport are checked against
  // the latest reading, which costs no syscall (clock_gettime is a ~30 µs syscall inside UML).
  uint64_t now_us() const override { return last_now_us_ = clock_->now_us(); }

  size_t backlog_size() const { return backlog_.size(); }

 protected:
  explicit QueuedBus(const Clock* clock);

  // Hands up to kTxChunk frames to the transport without blocking; *sent says how many it
  // took. kOk: all; kWouldBlock: transport full; anything else: a hard failure.
  virtual CanStatus transmit(const CanFrame* frames, size_t count, size_t* sent) = 0;
  // Whether the transport can carry this (valid) frame, e.g. FD on a classic interface.
  virtual bool supports(const CanFrame& frame) const = 0;

  // Retries the backlog; call before receiving and waiting as well.
  void flush_backlog();

  CanStats stats_;
  BusState state_ = BusState::kErrorActive;

 private:
  const Clock* clock_;
  mutable uint64_t last_now_us_ = 0;
  RingQueue<PendingFrame, kBacklogDepth> backlog_;
};

}  // namespace curio::hal
