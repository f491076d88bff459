// The receive side shared by the Linux socket backends (SocketCAN, UDP): batched reads
// (recvmmsg), receive_wait's wait-and-read in one syscall (SO_RCVTIMEO, set only when the
// timeout changes) and the ppoll wait. A backend opens the socket and decodes what it reads;
// the TX backlog is QueuedBus's. OS headers stay in the .cpp files.
#pragma once
#include <cstddef>
#include <cstdint>

#include "hal/host/queued_bus.hpp"

struct msghdr;

namespace curio::hal {

class SocketBus : public QueuedBus {
 public:
  static constexpr size_t kRxChunk = 64;  // datagrams per recvmmsg() call
  // Receive buffer per datagram; a backend's RxLayout stays within these.
  static constexpr size_t kMaxDatagramBytes = 80;
  static constexpr size_t kMaxNameBytes = 16;     // sockaddr_in
  static constexpr size_t kMaxControlBytes = 32;  // one 32-bit control message
  // How many times one read retries a failure recover() handled.
  static constexpr int kMaxRecoveries = 4;

  // What each read asks the kernel for, per datagram.
  struct RxLayout {
    size_t datagram_bytes = 0;  // payload buffer (one more than the largest valid datagram
                                // lets the decoder see oversized ones)
    size_t name_bytes = 0;      // source address (msg_name); 0: not wanted
    size_t control_bytes = 0;   // ancillary data (msg_control); 0: not wanted
  };

  ~SocketBus() override;  // closes the socket

  CanStatus receive_batch(CanFrame* out, size_t capacity, size_t* received) final;
  CanStatus wait_readable(uint64_t timeout_us) final;
  CanStatus receive_wait(CanFrame* out, size_t capacity, size_t* received,
                         uint64_t timeout_us) final;

  // The socket, for a caller that waits on it together with other descriptors (poll()
  // POLLIN, then receive_batch); curio-can slcan-bridge does. Reading it directly would
  // bypass the backend's decoding.
  int pollable_fd() const { return fd_; }

 protected:
  // Takes ownership of `fd`, a blocking socket: every read but receive_wait's first passes
  // MSG_DONTWAIT, so that one recvmmsg(MSG_WAITFORONE) can wait and read at once.
  SocketBus(int fd, const RxLayout& layout, const Clock* clock);

  int fd() const { return fd_; }

  // Turns one received datagram (`header` carries its name and control data) into *out, a
  // default CanFrame.
  // True: deliver it. False: consumed here (a control message, an error frame the caller did
  // not ask for, a filtered frame, malformed input), counted by the backend as it sees fit.
  virtual bool decode(const msghdr& header, const uint8_t* data, size_t size, CanFrame* out) = 0;
  // A read failed with `err` (neither EINTR nor EAGAIN) before waiting. True: handled, read
  // again with the same wait; false: count it in errors and stop reading.
  virtual bool recover(int err) {
    (void)err;
    return false;
  }
  // ppoll reported POLLERR. True: the socket counts as readable (the next read reports the
  // error); false: handled here, keep waiting for POLLIN.
  virtual bool on_poll_error() = 0;

 private:
  // Reads frames; when block_us > 0 the first read blocks up to that long (one syscall).
  // kTimeout: the blocking wait ran out; kEmpty: nothing deliverable.
  CanStatus read_frames(CanFrame* out, size_t capacity, size_t* received, uint64_t block_us);

  int fd_;
  RxLayout layout_;
  uint64_t rcvtimeo_us_ = 0;  // SO_RCVTIMEO now set on the socket (0 = none yet)
};

}  // namespace curio::hal
