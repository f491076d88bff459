// SocketCAN backend (Linux raw CAN socket): classic and FD frames, kernel-side acceptance
// filters, error frames opt-in, batched syscalls (sendmmsg/recvmmsg: inside User-mode Linux
// each syscall costs ~20 µs). OS headers stay in the .cpp.
#pragma once
#include <memory>
#include <string>

#include "hal/host/queued_bus.hpp"

namespace curio::hal {

struct SocketCanOptions {
  bool error_frames = false;  // deliver controller error frames to receive() (kFlagError)
};

class SocketCanBus final : public QueuedBus {
 public:
  // Opens `ifname` (e.g. "vcan0"); null with *error set when it cannot (no AF_CAN in this
  // kernel, no such interface, ...).
  static std::unique_ptr<SocketCanBus> open(const std::string& ifname,
                                            const SocketCanOptions& options, std::string* error,
                                            const Clock* clock = nullptr);
  ~SocketCanBus() override;

  CanStatus receive_batch(CanFrame* out, size_t capacity, size_t* received) override;
  CanStatus wait_readable(uint64_t timeout_us) override;
  CanStatus receive_wait(CanFrame* out, size_t capacity, size_t* received,
                         uint64_t timeout_us) override;
  CanStatus set_filters(const CanFilter* filters, size_t count) override;

  bool fd_capable() const { return fd_capable_; }

 protected:
  CanStatus transmit(const CanFrame* frames, size_t count, size_t* sent) override;
  bool supports(const CanFrame& frame) const override { return fd_capable_ || !frame.fd(); }

 private:
  SocketCanBus(int fd, bool fd_capable, const SocketCanOptions& options, const Clock* clock);
  // Reads frames; when block_us > 0 the first read blocks up to that long (one syscall).
  CanStatus read_frames(CanFrame* out, size_t capacity, size_t* received, uint64_t block_us);
  // Updates state and counters from a kernel error frame (id and data as received).
  void on_error_frame(uint32_t err_class, const uint8_t* data);

  int fd_;
  bool fd_capable_;
  SocketCanOptions options_;
  uint64_t rcvtimeo_us_ = 0;  // SO_RCVTIMEO now set on the socket (0 = none yet)
};

}  // namespace curio::hal
