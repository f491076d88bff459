// SocketCAN backend (Linux raw CAN socket): classic and FD frames, kernel-side acceptance
// filters, error frames opt-in, batched syscalls (sendmmsg/recvmmsg: inside User-mode Linux
// each syscall costs ~20 µs). OS headers stay in the .cpp.
#pragma once
#include <memory>
#include <string>

#include "hal/linux/socket_bus.hpp"

namespace curio::hal {

struct SocketCanOptions {
  bool error_frames = false;  // deliver controller error frames to receive() (kFlagError)
};

class SocketCanBus final : public SocketBus {
 public:
  // Opens `ifname` (e.g. "vcan0"); null with *error set when it cannot (no AF_CAN in this
  // kernel, no such interface, ...).
  static std::unique_ptr<SocketCanBus> open(const std::string& ifname,
                                            const SocketCanOptions& options, std::string* error,
                                            const Clock* clock = nullptr);

  CanStatus set_filters(const CanFilter* filters, size_t count) override;

  // FD needs an interface with MTU 72 (and the socket option, which this sets when it can).
  bool carries_fd() const override { return fd_capable_; }

 protected:
  CanStatus transmit(const CanFrame* frames, size_t count, size_t* sent) override;
  bool supports(const CanFrame& frame) const override { return fd_capable_ || !frame.fd(); }
  // A kernel frame (classic or FD) or error frame; also picks up the RX overflow counter.
  bool decode(const msghdr& header, const uint8_t* data, size_t size, CanFrame* out) override;
  // A pending socket error is reported by the next read.
  bool on_poll_error() override { return true; }

 private:
  SocketCanBus(int fd, bool fd_capable, const SocketCanOptions& options, const Clock* clock);
  // Updates state and counters from a kernel error frame (id and data as received).
  void on_error_frame(uint32_t err_class, const uint8_t* data);

  bool fd_capable_;
  SocketCanOptions options_;
};

}  // namespace curio::hal
