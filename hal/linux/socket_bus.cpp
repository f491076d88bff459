#include "hal/linux/socket_bus.hpp"

#include <errno.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

namespace curio::hal {

SocketBus::SocketBus(int fd, const RxLayout& layout, const Clock* clock)
    : QueuedBus(clock), fd_(fd), layout_(layout) {
  // The backends check their layout at compile time; this only keeps the buffers in bounds.
  layout_.datagram_bytes = std::min(layout_.datagram_bytes, kMaxDatagramBytes);
  layout_.name_bytes = std::min(layout_.name_bytes, kMaxNameBytes);
  layout_.control_bytes = std::min(layout_.control_bytes, kMaxControlBytes);
}

SocketBus::~SocketBus() {
  ::close(fd_);
}

CanStatus SocketBus::receive_batch(CanFrame* out, size_t capacity, size_t* received) {
  flush_backlog();
  return read_frames(out, capacity, received, 0);
}

CanStatus SocketBus::receive_wait(CanFrame* out, size_t capacity, size_t* received,
                                  uint64_t timeout_us) {
  flush_backlog();
  if (backlog_size() > 0 || timeout_us == 0) {  // must also watch for POLLOUT: generic path
    return CanBus::receive_wait(out, capacity, received, timeout_us);
  }
  // First wait: the whole timeout, no clock read. Only if frames arrived but none could be
  // delivered (filtered, error frames, control datagrams) is the clock read, and the rest of
  // the wait is then measured from there (so the total may reach twice the timeout).
  CanStatus s = read_frames(out, capacity, received, timeout_us);
  if (s != CanStatus::kEmpty) return s;
  const uint64_t end = now_us() + timeout_us;
  for (;;) {
    const uint64_t now = now_us();
    if (now >= end) {
      if (received) *received = 0;
      return CanStatus::kTimeout;
    }
    s = read_frames(out, capacity, received, end - now);
    if (s != CanStatus::kEmpty) return s;
  }
}

CanStatus SocketBus::read_frames(CanFrame* out, size_t capacity, size_t* received,
                                 uint64_t block_us) {
  size_t n = 0;
  bool timed_out = false;
  if (block_us > 0 && block_us != rcvtimeo_us_) {
    const timeval tv{static_cast<time_t>(block_us / 1000000),
                     static_cast<suseconds_t>(block_us % 1000000)};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
    rcvtimeo_us_ = block_us;
  }
  int recoveries = 0;
  // Datagrams the decoder consumes (control messages, unwanted error frames, filtered
  // frames) do not end the read: it goes on until something is delivered or the socket is
  // drained.
  while (n < capacity) {
    const size_t want = std::min(capacity - n, kRxChunk);
    alignas(8) uint8_t buf[kRxChunk][kMaxDatagramBytes];
    alignas(8) uint8_t names[kRxChunk][kMaxNameBytes];
    alignas(cmsghdr) uint8_t ctrl[kRxChunk][kMaxControlBytes];
    iovec iov[kRxChunk];
    mmsghdr msgs[kRxChunk];
    std::memset(msgs, 0, sizeof(mmsghdr) * want);
    for (size_t i = 0; i < want; ++i) {
      iov[i] = {buf[i], layout_.datagram_bytes};
      msghdr& h = msgs[i].msg_hdr;
      h.msg_iov = &iov[i];
      h.msg_iovlen = 1;
      if (layout_.name_bytes > 0) {
        h.msg_name = names[i];
        h.msg_namelen = static_cast<socklen_t>(layout_.name_bytes);
      }
      if (layout_.control_bytes > 0) {
        h.msg_control = ctrl[i];
        h.msg_controllen = layout_.control_bytes;
      }
    }
    const int flags = (block_us > 0 && n == 0) ? MSG_WAITFORONE : MSG_DONTWAIT;
    const int r = ::recvmmsg(fd_, msgs, static_cast<unsigned>(want), flags, nullptr);
    const int err = r < 0 ? errno : 0;
    // A failure the backend handles (UDP: a queued ICMP error) came before any wait, so the
    // retry keeps the wait.
    if (r < 0 && err != EINTR && err != EAGAIN && recoveries < kMaxRecoveries && recover(err)) {
      ++recoveries;
      continue;
    }
    block_us = 0;  // block at most once per call; after a signal receive_wait re-waits
    if (r < 0 && err == EINTR) continue;
    if (r <= 0) {
      if (r < 0 && err == EAGAIN && flags == MSG_WAITFORONE) timed_out = true;
      if (r < 0 && err != EAGAIN) ++stats_.errors;
      break;
    }
    for (int i = 0; i < r; ++i) {
      CanFrame f;
      if (decode(msgs[i].msg_hdr, buf[i], msgs[i].msg_len, &f)) out[n++] = f;
    }
    // Fewer datagrams than asked for: the socket is drained, skip the EAGAIN round trip.
    if (static_cast<size_t>(r) < want) break;
  }
  stats_.rx_frames += n;
  if (received) *received = n;
  if (n > 0) return CanStatus::kOk;
  return timed_out ? CanStatus::kTimeout : CanStatus::kEmpty;
}

CanStatus SocketBus::wait_readable(uint64_t timeout_us) {
  const uint64_t end = now_us() + timeout_us;
  for (;;) {
    flush_backlog();
    const uint64_t now = now_us();
    const uint64_t left = end > now ? end - now : 0;
    pollfd p{fd_, static_cast<short>(POLLIN | (backlog_size() > 0 ? POLLOUT : 0)), 0};
    const timespec ts{static_cast<time_t>(left / 1000000),
                      static_cast<long>(left % 1000000) * 1000};
    const int r = ::ppoll(&p, 1, &ts, nullptr);
    if (r < 0 && errno != EINTR) {
      ++stats_.errors;
      return CanStatus::kIoError;
    }
    if (r > 0 && (p.revents & POLLERR) && on_poll_error()) return CanStatus::kOk;
    if (r > 0 && (p.revents & POLLIN)) return CanStatus::kOk;
    if (now_us() >= end) return CanStatus::kTimeout;
  }
}

}  // namespace curio::hal
