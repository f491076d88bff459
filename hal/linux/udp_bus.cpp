#include "hal/linux/udp_bus.hpp"

#include <arpa/inet.h>
#include <errno.h>
#include <linux/errqueue.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

namespace curio::hal {
namespace {

constexpr size_t kDatagramMax = kUdpHeaderBytes + kFdMaxLen;
constexpr size_t kRxChunk = 64;
constexpr int kBufBytes = 4 << 20;
constexpr uint8_t kHello = 'H';
constexpr uint8_t kBye = 'B';

sockaddr_in loopback_addr(uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // 127.0.0.1 and nothing else, ever
  return a;
}

}  // namespace

size_t encode_udp_datagram(const CanFrame& f, uint8_t* out) {
  out[0] = kUdpMagic;
  out[1] = kUdpVersion;
  out[2] = f.flags;
  out[3] = f.len;
  for (int i = 0; i < 4; ++i) out[4 + i] = static_cast<uint8_t>(f.id >> (8 * i));
  std::memcpy(out + kUdpHeaderBytes, f.data, f.len);
  return kUdpHeaderBytes + f.len;
}

bool decode_udp_datagram(const uint8_t* data, size_t size, CanFrame* out) {
  if (size < kUdpHeaderBytes || data[0] != kUdpMagic || data[1] != kUdpVersion) return false;
  CanFrame f;
  f.flags = data[2];
  f.len = data[3];
  for (int i = 0; i < 4; ++i) f.id |= static_cast<uint32_t>(data[4 + i]) << (8 * i);
  if (f.len > kFdMaxLen || size != kUdpHeaderBytes + f.len) return false;
  std::memcpy(f.data, data + kUdpHeaderBytes, f.len);
  if (!is_valid(f) || f.error()) return false;
  *out = f;
  return true;
}

std::unique_ptr<UdpBus> UdpBus::open(uint16_t base_port, unsigned ports, std::string* error,
                                     const Clock* clock) {
  const std::string where = "udp:127.0.0.1:" + std::to_string(base_port);
  auto fail = [&](const std::string& msg, int fd) -> std::unique_ptr<UdpBus> {
    if (error) *error = where + ": " + msg;
    if (fd >= 0) ::close(fd);
    return nullptr;
  };
  if (ports < 2 || ports > kUdpMaxPorts) {
    return fail("port count must be 2.." + std::to_string(kUdpMaxPorts), -1);
  }
  if (base_port == 0 || static_cast<unsigned>(base_port) + ports - 1 > 65535u) {
    return fail("port range out of 1..65535", -1);
  }
  // A blocking socket (every call but receive_wait passes MSG_DONTWAIT) so that one
  // recvmmsg(MSG_WAITFORONE) can wait and read at once.
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return fail(std::string("socket: ") + std::strerror(errno), -1);
  // Every endpoint must own its port: SO_REUSEADDR/REUSEPORT stay off on purpose.
  uint16_t port = 0;
  for (unsigned i = 0; i < ports && port == 0; ++i) {
    const sockaddr_in a = loopback_addr(static_cast<uint16_t>(base_port + i));
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof(a)) == 0) {
      port = static_cast<uint16_t>(base_port + i);
    } else if (errno != EADDRINUSE) {
      return fail(std::string("bind: ") + std::strerror(errno), fd);
    }
  }
  if (port == 0) {
    return fail("all " + std::to_string(ports) +
                    " ports of the bus are in use (too many endpoints, or another program owns "
                    "them; pick another PORT)",
                fd);
  }
  const int on = 1;
  if (::setsockopt(fd, IPPROTO_IP, IP_RECVERR, &on, sizeof(on)) < 0) {
    return fail(std::string("IP_RECVERR: ") + std::strerror(errno), fd);
  }
  if (::setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &kBufBytes, sizeof(kBufBytes)) < 0) {
    ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &kBufBytes, sizeof(kBufBytes));
  }
  if (::setsockopt(fd, SOL_SOCKET, SO_SNDBUFFORCE, &kBufBytes, sizeof(kBufBytes)) < 0) {
    ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &kBufBytes, sizeof(kBufBytes));
  }
  std::unique_ptr<UdpBus> bus(new UdpBus(fd, base_port, ports, port, clock));
  bus->announce(kHello);
  return bus;
}

UdpBus::UdpBus(int fd, uint16_t base_port, unsigned ports, uint16_t port, const Clock* clock)
    : QueuedBus(clock), fd_(fd), base_port_(base_port), ports_(ports), port_(port) {}

UdpBus::~UdpBus() {
  announce(kBye);
  ::close(fd_);
}

void UdpBus::announce(uint8_t kind) {
  uint8_t msg[kUdpHeaderBytes] = {kind, kUdpVersion, 0, 0, 0, 0, 0, 0};
  for (unsigned i = 0; i < ports_; ++i) {
    const auto p = static_cast<uint16_t>(base_port_ + i);
    if (p == port_) continue;
    const sockaddr_in a = loopback_addr(p);
    ::sendto(fd_, msg, sizeof(msg), MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&a), sizeof(a));
  }
}

void UdpBus::drain_error_queue() {
  for (;;) {
    uint8_t payload[kDatagramMax];
    iovec iov{payload, sizeof(payload)};
    sockaddr_in dest{};
    alignas(cmsghdr) uint8_t ctrl[256];
    msghdr h{};
    h.msg_name = &dest;
    h.msg_namelen = sizeof(dest);
    h.msg_iov = &iov;
    h.msg_iovlen = 1;
    h.msg_control = ctrl;
    h.msg_controllen = sizeof(ctrl);
    const ssize_t n = ::recvmsg(fd_, &h, MSG_ERRQUEUE | MSG_DONTWAIT);
    if (n < 0) return;
    // Only a lost frame proves a port dead: a hello sent before that peer bound says nothing
    // about it now.
    if (n < 1 || payload[0] != kUdpMagic) continue;
    for (cmsghdr* c = CMSG_FIRSTHDR(&h); c != nullptr; c = CMSG_NXTHDR(&h, c)) {
      if (c->cmsg_level != IPPROTO_IP || c->cmsg_type != IP_RECVERR) continue;
      sock_extended_err ee;
      std::memcpy(&ee, CMSG_DATA(c), sizeof(ee));
      const unsigned p = ntohs(dest.sin_port);
      if (ee.ee_origin == SO_EE_ORIGIN_ICMP && ee.ee_errno == ECONNREFUSED && p >= base_port_ &&
          p < base_port_ + ports_) {
        dead_until_us_[p - base_port_] = now_us() + kUdpDeadProbeUs;
      }
    }
  }
}

CanStatus UdpBus::transmit(const CanFrame* frames, size_t count, size_t* sent) {
  count = std::min(count, kTxChunk);
  *sent = 0;
  if (count == 0) return CanStatus::kOk;
  const uint64_t now = now_us();
  sockaddr_in dest[kUdpMaxPorts];
  size_t peers = 0;
  for (unsigned i = 0; i < ports_; ++i) {
    const auto p = static_cast<uint16_t>(base_port_ + i);
    if (p != port_ && now >= dead_until_us_[i]) dest[peers++] = loopback_addr(p);
  }
  if (peers == 0) {  // alone on the bus: the frame is on the wire, nobody hears it
    *sent = count;
    return CanStatus::kOk;
  }
  uint8_t buf[kTxChunk][kDatagramMax];
  iovec iov[kTxChunk];
  // Fixed storage: the send path allocates nothing (it runs once per control period).
  mmsghdr msgs[kTxChunk * kUdpMaxPorts];
  const size_t n_msgs = count * peers;
  for (size_t i = 0; i < count; ++i) {
    iov[i] = {buf[i], encode_udp_datagram(frames[i], buf[i])};
    for (size_t j = 0; j < peers; ++j) {
      msghdr& h = msgs[i * peers + j].msg_hdr;
      h = msghdr{};
      h.msg_name = &dest[j];
      h.msg_namelen = sizeof(sockaddr_in);
      h.msg_iov = &iov[i];
      h.msg_iovlen = 1;
    }
  }
  size_t done = 0;
  while (done < n_msgs) {
    const int r = ::sendmmsg(fd_, msgs + done, static_cast<unsigned>(n_msgs - done), MSG_DONTWAIT);
    if (r < 0) {
      // A pending ICMP error from an earlier datagram to an unbound port: learn, retry.
      if (errno == ECONNREFUSED) {
        drain_error_queue();
        continue;
      }
      if (errno == EAGAIN || errno == ENOBUFS) break;
      ++stats_.errors;
      *sent = done / peers;
      return CanStatus::kIoError;
    }
    done += static_cast<size_t>(r);
  }
  // A frame that reached only some peers counts as sent (they would lose it on a full
  // socket anyway); the rest wait in the backlog.
  *sent = (done + peers - 1) / peers;
  return *sent == count ? CanStatus::kOk : CanStatus::kWouldBlock;
}

CanStatus UdpBus::receive_batch(CanFrame* out, size_t capacity, size_t* received) {
  flush_backlog();
  return read_frames(out, capacity, received, 0);
}

CanStatus UdpBus::receive_wait(CanFrame* out, size_t capacity, size_t* received,
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

CanStatus UdpBus::read_frames(CanFrame* out, size_t capacity, size_t* received, uint64_t block_us) {
  size_t n = 0;
  bool timed_out = false;
  if (block_us > 0 && block_us != rcvtimeo_us_) {
    const timeval tv{static_cast<time_t>(block_us / 1000000),
                     static_cast<suseconds_t>(block_us % 1000000)};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
    rcvtimeo_us_ = block_us;
  }
  int refused = 0;
  while (n < capacity) {
    const size_t want = std::min(capacity - n, kRxChunk);
    uint8_t buf[kRxChunk][kDatagramMax + 1];  // +1 detects oversized datagrams
    iovec iov[kRxChunk];
    sockaddr_in from[kRxChunk];
    mmsghdr msgs[kRxChunk];
    std::memset(msgs, 0, sizeof(mmsghdr) * want);
    for (size_t i = 0; i < want; ++i) {
      iov[i] = {buf[i], sizeof(buf[i])};
      msgs[i].msg_hdr.msg_iov = &iov[i];
      msgs[i].msg_hdr.msg_iovlen = 1;
      msgs[i].msg_hdr.msg_name = &from[i];
      msgs[i].msg_hdr.msg_namelen = sizeof(from[i]);
    }
    const int flags = (block_us > 0 && n == 0) ? MSG_WAITFORONE : MSG_DONTWAIT;
    const int r = ::recvmmsg(fd_, msgs, static_cast<unsigned>(want), flags, nullptr);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0 && errno == ECONNREFUSED && refused++ < 4) {
      drain_error_queue();
      continue;
    }
    block_us = 0;  // block at most once per call
    if (r <= 0) {
      if (r < 0 && errno == EAGAIN && flags == MSG_WAITFORONE) timed_out = true;
      if (r < 0 && errno != EAGAIN) ++stats_.errors;
      break;
    }
    for (int i = 0; i < r; ++i) {
      const unsigned src_port = ntohs(from[i].sin_port);
      const bool from_bus = from[i].sin_addr.s_addr == htonl(INADDR_LOOPBACK) &&
                            src_port >= base_port_ && src_port < base_port_ + ports_ &&
                            src_port != port_;
      if (!from_bus) {
        ++stats_.errors;
        continue;
      }
      const uint8_t* d = buf[i];
      uint64_t& dead_until = dead_until_us_[src_port - base_port_];
      if (msgs[i].msg_len == kUdpHeaderBytes && d[1] == kUdpVersion &&
          (d[0] == kHello || d[0] == kBye)) {
        dead_until = d[0] == kHello ? 0 : now_us() + kUdpDeadProbeUs;
        continue;
      }
      CanFrame f;
      if (!decode_udp_datagram(d, msgs[i].msg_len, &f)) {
        ++stats_.errors;
        continue;
      }
      dead_until = 0;  // it talks, so it listens
      if (!filters_accept(filters_, filter_count_, f)) {
        ++stats_.rx_filtered;
        continue;
      }
      out[n++] = f;
    }
    // Fewer datagrams than asked for: the socket is drained, skip the EAGAIN round trip.
    if (static_cast<size_t>(r) < want) break;
    if (static_cast<size_t>(r) < want) break;
  }
  stats_.rx_frames += n;
  if (received) *received = n;
  // kTimeout: the blocking wait ran out; kEmpty: frames came, none deliverable.
  if (n > 0) return CanStatus::kOk;
  return timed_out ? CanStatus::kTimeout : CanStatus::kEmpty;
}

CanStatus UdpBus::wait_readable(uint64_t timeout_us) {
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
    if (r > 0 && (p.revents & POLLERR)) drain_error_queue();
    if (r > 0 && (p.revents & POLLIN)) return CanStatus::kOk;
    if (now_us() >= end) return CanStatus::kTimeout;
  }
}

CanStatus UdpBus::set_filters(const CanFilter* filters, size_t count) {
  if (count > kMaxFilters) return CanStatus::kTooManyFilters;
  for (size_t i = 0; i < count; ++i) filters_[i] = filters[i];
  filter_count_ = count;
  return CanStatus::kOk;
}

}  // namespace curio::hal
