#include "hal/linux/udp_bus.hpp"

#include <arpa/inet.h>
#include <errno.h>
#include <linux/errqueue.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

namespace curio::hal {
namespace {

constexpr size_t kDatagramMax = kUdpHeaderBytes + kFdMaxLen;
constexpr int kBufBytes = 4 << 20;
constexpr uint8_t kHello = 'H';
constexpr uint8_t kBye = 'B';
// One datagram (one byte more than the largest, to see oversized ones) and its sender.
constexpr SocketBus::RxLayout kRxLayout{kDatagramMax + 1, sizeof(sockaddr_in), 0};
static_assert(kRxLayout.datagram_bytes <= SocketBus::kMaxDatagramBytes &&
              kRxLayout.name_bytes <= SocketBus::kMaxNameBytes);

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
                                     const Clock* clock, bool carries_fd) {
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
  std::unique_ptr<UdpBus> bus(new UdpBus(fd, base_port, ports, port, clock, carries_fd));
  bus->announce(kHello);
  return bus;
}

UdpBus::UdpBus(int fd, uint16_t base_port, unsigned ports, uint16_t port, const Clock* clock,
               bool carries_fd)
    : SocketBus(fd, kRxLayout, clock),
      base_port_(base_port),
      ports_(ports),
      port_(port),
      carries_fd_(carries_fd) {}

UdpBus::~UdpBus() {
  announce(kBye);
}

void UdpBus::announce(uint8_t kind) {
  uint8_t msg[kUdpHeaderBytes] = {kind, kUdpVersion, 0, 0, 0, 0, 0, 0};
  for (unsigned i = 0; i < ports_; ++i) {
    const auto p = static_cast<uint16_t>(base_port_ + i);
    if (p == port_) continue;
    const sockaddr_in a = loopback_addr(p);
    ::sendto(fd(), msg, sizeof(msg), MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&a),
             sizeof(a));
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
    const ssize_t n = ::recvmsg(fd(), &h, MSG_ERRQUEUE | MSG_DONTWAIT);
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
    const int r = ::sendmmsg(fd(), msgs + done, static_cast<unsigned>(n_msgs - done), MSG_DONTWAIT);
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

bool UdpBus::decode(const msghdr& header, const uint8_t* data, size_t size, CanFrame* out) {
  sockaddr_in from;
  std::memcpy(&from, header.msg_name, sizeof(from));
  const unsigned src_port = ntohs(from.sin_port);
  const bool from_bus = from.sin_addr.s_addr == htonl(INADDR_LOOPBACK) && src_port >= base_port_ &&
                        src_port < base_port_ + ports_ && src_port != port_;
  if (!from_bus) {
    ++stats_.errors;
    return false;
  }
  uint64_t& dead_until = dead_until_us_[src_port - base_port_];
  if (size == kUdpHeaderBytes && data[1] == kUdpVersion && (data[0] == kHello || data[0] == kBye)) {
    dead_until = data[0] == kHello ? 0 : now_us() + kUdpDeadProbeUs;
    return false;
  }
  if (!decode_udp_datagram(data, size, out)) {
    ++stats_.errors;
    return false;
  }
  dead_until = 0;  // it talks, so it listens
  if (out->fd() && !carries_fd_) {  // a classic controller cannot read an FD frame
    ++stats_.errors;
    return false;
  }
  if (!filters_accept(filters_, filter_count_, *out)) {
    ++stats_.rx_filtered;
    return false;
  }
  return true;
}

bool UdpBus::recover(int err) {
  if (err != ECONNREFUSED) return false;
  drain_error_queue();
  return true;
}

bool UdpBus::on_poll_error() {
  drain_error_queue();
  return false;
}

CanStatus UdpBus::set_filters(const CanFilter* filters, size_t count) {
  if (count > kMaxFilters) return CanStatus::kTooManyFilters;
  for (size_t i = 0; i < count; ++i) filters_[i] = filters[i];
  filter_count_ = count;
  return CanStatus::kOk;
}

}  // namespace curio::hal
