// An in-image CAN bus between the controller and the FakeArm: the controller's endpoint of a
// hal::CanBus whose other side is the arm, in the same thread. Frames the controller sends
// are handed to the arm at once; the arm's answers wait in a fixed queue for the controller's
// receive calls. Time is virtual and deterministic: every frame on the wire (either way)
// takes kFrameUs, and a wait with nothing pending jumps to the arm's next heartbeat or to
// the end of the timeout. Heartbeats come due as time passes, so the controller's heartbeat
// consumer runs as on a real bus. Firmware-clean: no heap, no OS, no locking.
#pragma once
#include <cstddef>
#include <cstdint>

#include "tests/app/qemu_app/fake_arm.hpp"
#include "hal/can_bus.hpp"

namespace curio::test {

class ImageBus final : public hal::CanBus {
 public:
  // ~one 8-byte classic frame at 1 Mbit/s (≈ 110 bits with stuffing).
  static constexpr uint64_t kFrameUs = 110;

  void attach(FakeArm* arm) { arm_ = arm; }
  FakeArm::OutQueue* arm_out() { return &to_controller_; }

  hal::CanStatus send_batch(const hal::CanFrame* frames, size_t count, uint64_t deadline_us,
                            size_t* accepted) override {
    size_t n = 0;
    for (; n < count; ++n) {
      if (!hal::is_valid(frames[n])) {
        ++stats_.tx_rejected;
        if (accepted != nullptr) *accepted = n;
        return hal::CanStatus::kInvalidFrame;
      }
      now_ += kFrameUs;
      if (now_ > deadline_us) {  // cannot happen here; counted as a real bus would
        ++stats_.tx_timedout;
        continue;
      }
      ++stats_.tx_frames;
      arm_->tick(now_);
      arm_->handle(frames[n], now_);
    }
    if (accepted != nullptr) *accepted = n;
    return hal::CanStatus::kOk;
  }

  hal::CanStatus receive_batch(hal::CanFrame* out, size_t capacity, size_t* received) override {
    arm_->tick(now_);
    size_t n = 0;
    while (n < capacity && to_controller_.pop(&out[n])) {
      now_ += kFrameUs;
      ++n;
    }
    stats_.rx_frames += n;
    if (received != nullptr) *received = n;
    return n > 0 ? hal::CanStatus::kOk : hal::CanStatus::kEmpty;
  }

  hal::CanStatus wait_readable(uint64_t timeout_us) override {
    const uint64_t end = now_ + timeout_us;
    arm_->tick(now_);
    // Nothing pending: time passes in 1 ms ticks (the arm's heartbeats come due) until a
    // frame is there or the timeout ends.
    while (to_controller_.empty() && now_ < end) {
      now_ = end - now_ > 1000 ? now_ + 1000 : end;
      arm_->tick(now_);
    }
    return to_controller_.empty() ? hal::CanStatus::kTimeout : hal::CanStatus::kOk;
  }

  hal::CanStatus set_filters(const hal::CanFilter*, size_t count) override {
    return count <= kMaxFilters ? hal::CanStatus::kOk : hal::CanStatus::kTooManyFilters;
  }
  hal::CanStats stats() const override { return stats_; }
  hal::BusState state() const override { return hal::BusState::kErrorActive; }
  bool carries_fd() const override { return true; }
  uint64_t now_us() const override { return now_; }

 private:
  FakeArm* arm_ = nullptr;
  FakeArm::OutQueue to_controller_;
  uint64_t now_ = 0;
  hal::CanStats stats_;
};

}  // namespace curio::test
