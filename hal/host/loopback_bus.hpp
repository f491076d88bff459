// In-process CAN bus: several endpoints (CanBus objects) on one LoopbackBus. Each endpoint
// receives every other endpoint's frames (never its own, like SocketCAN's default), in the
// global order of the send calls, so single-threaded tests are deterministic. Thread-safe:
// the simulator and the controller may run in different threads of one process.
// Fault injection: pause the wire (frames wait, deadlines keep running) and force a node's
// controller state (e.g. bus-off).
#pragma once
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>

#include "hal/can_bus.hpp"
#include "hal/clock.hpp"
#include "hal/frame_queue.hpp"

namespace curio::hal {

class LoopbackEndpoint;

class LoopbackBus : public std::enable_shared_from_this<LoopbackBus> {
 public:
  static constexpr size_t kMaxEndpoints = 16;
  // Per endpoint: more than one 12 KB ISO-TP burst (1,757 frames in the classic profile).
  static constexpr size_t kRxDepth = 2048;
  static constexpr size_t kPendingDepth = 256;  // frames held while the wire is paused

  // clock: deadlines are judged on it (null: the host's steady clock). It must outlive the bus.
  static std::shared_ptr<LoopbackBus> create(const Clock* clock = nullptr);

  // A new node on this bus; null when kMaxEndpoints are open. A node without FD
  // (carries_fd false: a classic-only controller) refuses to send FD frames and does not hear
  // those of others (counted in its errors).
  std::unique_ptr<LoopbackEndpoint> open(bool carries_fd = true);

  // While paused, sends are queued (up to kPendingDepth); resuming delivers them in order,
  // dropping those whose deadline has passed (counted as the sender's tx_timedout).
  void set_tx_paused(bool paused);

  size_t endpoint_count() const;

 private:
  friend class LoopbackEndpoint;
  struct Pending {
    CanFrame frame;
    uint64_t deadline_us = 0;
    size_t sender = 0;
  };

  explicit LoopbackBus(const Clock* clock) : clock_(clock) {}
  void deliver_locked(size_t sender, const CanFrame& frame);
  void flush_pending_locked();

  const Clock* clock_;
  mutable std::mutex mutex_;
  std::condition_variable readable_;
  LoopbackEndpoint* endpoints_[kMaxEndpoints] = {};
  RingQueue<Pending, kPendingDepth> pending_;
  bool paused_ = false;
};

class LoopbackEndpoint final : public CanBus {
 public:
  ~LoopbackEndpoint() override;

  CanStatus send_batch(const CanFrame* frames, size_t count, uint64_t deadline_us,
                       size_t* accepted) override;
  CanStatus receive_batch(CanFrame* out, size_t capacity, size_t* received) override;
  CanStatus wait_readable(uint64_t timeout_us) override;
  CanStatus set_filters(const CanFilter* filters, size_t count) override;
  CanStats stats() const override;
  BusState state() const override;
  uint64_t now_us() const override;
  bool carries_fd() const override { return carries_fd_; }

  // Fault injection: what this node's controller reports; bus-off and down refuse sends.
  void force_state(BusState state);

 private:
  friend class LoopbackBus;
  LoopbackEndpoint(std::shared_ptr<LoopbackBus> bus, size_t index, bool carries_fd)
      : bus_(std::move(bus)), index_(index), carries_fd_(carries_fd) {}

  std::shared_ptr<LoopbackBus> bus_;
  size_t index_;
  bool carries_fd_;
  FrameQueue<LoopbackBus::kRxDepth> rx_;
  CanFilter filters_[kMaxFilters] = {};
  size_t filter_count_ = 0;
  CanStats stats_;
  BusState state_ = BusState::kErrorActive;
};

// Process-wide named loopback buses, so `loopback` / `loopback:NAME` URLs opened by different
// parts of one program meet on the same wire. The bus lives while an endpoint is open; the
// clock of the call that created it is the bus's clock.
std::shared_ptr<LoopbackBus> named_loopback_bus(const std::string& name,
                                                const Clock* clock = nullptr);

}  // namespace curio::hal
