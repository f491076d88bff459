#include "hal/linux/socketcan_bus.hpp"

#include <errno.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

namespace curio::hal {
namespace {

constexpr int kRcvBufBytes = 4 << 20;  // a 12 KB ISO-TP burst is ~200 skbs

// Controller errors that move the bus state; always subscribed so state() stays true.
constexpr can_err_mask_t kStateErrors = CAN_ERR_CRTL | CAN_ERR_BUSOFF | CAN_ERR_RESTARTED;

// One kernel frame (classic or FD) and the SO_RXQ_OVFL drop counter.
constexpr SocketBus::RxLayout kRxLayout{sizeof(canfd_frame), 0, CMSG_SPACE(sizeof(uint32_t))};
static_assert(kRxLayout.datagram_bytes <= SocketBus::kMaxDatagramBytes &&
              kRxLayout.control_bytes <= SocketBus::kMaxControlBytes);

std::string errno_text(const char* what) {
  return std::string(what) + ": " + std::strerror(errno);
}

void to_kernel(const CanFrame& f, canfd_frame* k) {
  std::memset(k, 0, sizeof(*k));
  k->can_id = f.id | (f.extended() ? CAN_EFF_FLAG : 0u) | (f.remote() ? CAN_RTR_FLAG : 0u);
  k->len = f.len;
  if (f.fd()) {
    k->flags = static_cast<uint8_t>(((f.flags & kFlagBrs) ? CANFD_BRS : 0) |
                                    ((f.flags & kFlagEsi) ? CANFD_ESI : 0));
  }
  std::memcpy(k->data, f.data, f.len);
}

}  // namespace

std::unique_ptr<SocketCanBus> SocketCanBus::open(const std::string& ifname,
                                                 const SocketCanOptions& options,
                                                 std::string* error, const Clock* clock) {
  auto fail = [&](std::string msg, int fd) -> std::unique_ptr<SocketCanBus> {
    if (error) *error = "socketcan:" + ifname + ": " + msg;
    if (fd >= 0) ::close(fd);
    return nullptr;
  };
  if (ifname.empty() || ifname.size() >= IFNAMSIZ) return fail("bad interface name", -1);
  // A blocking socket (every call but receive_wait passes MSG_DONTWAIT) so that one
  // recvmmsg(MSG_WAITFORONE) can wait and read at once.
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    const int e = errno;
    std::string msg = errno_text("socket(AF_CAN)");
    if (e == EAFNOSUPPORT) {
      msg += " (this kernel has no SocketCAN; run inside User-mode Linux: tests/uml/run-in-uml.sh)";
    }
    return fail(msg, -1);
  }
  ifreq ifr{};
  std::memcpy(ifr.ifr_name, ifname.c_str(), ifname.size() + 1);
  if (::ioctl(fd, SIOCGIFINDEX, &ifr) < 0) return fail(errno_text("no such interface"), fd);
  const int ifindex = ifr.ifr_ifindex;
  // FD frames need both the socket option and an interface with MTU 72.
  bool fd_capable = false;
  if (::ioctl(fd, SIOCGIFMTU, &ifr) == 0 && ifr.ifr_mtu == static_cast<int>(CANFD_MTU)) {
    const int on = 1;
    fd_capable = ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof(on)) == 0;
  }
  const can_err_mask_t err_mask = options.error_frames ? CAN_ERR_MASK : kStateErrors;
  if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof(err_mask)) < 0) {
    return fail(errno_text("CAN_RAW_ERR_FILTER"), fd);
  }
  const int on = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof(on));  // drop counter; best effort
  if (::setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &kRcvBufBytes, sizeof(kRcvBufBytes)) < 0) {
    ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &kRcvBufBytes, sizeof(kRcvBufBytes));
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifindex;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) < 0) {
    return fail(errno_text("bind"), fd);
  }
  return std::unique_ptr<SocketCanBus>(new SocketCanBus(fd, fd_capable, options, clock));
}

SocketCanBus::SocketCanBus(int fd, bool fd_capable, const SocketCanOptions& options,
                           const Clock* clock)
    : SocketBus(fd, kRxLayout, clock), fd_capable_(fd_capable), options_(options) {}

CanStatus SocketCanBus::transmit(const CanFrame* frames, size_t count, size_t* sent) {
  canfd_frame buf[kTxChunk];
  iovec iov[kTxChunk];
  mmsghdr msgs[kTxChunk];
  count = std::min(count, kTxChunk);
  std::memset(msgs, 0, sizeof(mmsghdr) * count);
  for (size_t i = 0; i < count; ++i) {
    to_kernel(frames[i], &buf[i]);
    iov[i].iov_base = &buf[i];
    iov[i].iov_len = frames[i].fd() ? CANFD_MTU : CAN_MTU;
    msgs[i].msg_hdr.msg_iov = &iov[i];
    msgs[i].msg_hdr.msg_iovlen = 1;
  }
  *sent = 0;
  if (count == 0) return CanStatus::kOk;
  const int r = ::sendmmsg(fd(), msgs, static_cast<unsigned>(count), MSG_DONTWAIT);
  if (r < 0) {
    if (errno == EAGAIN || errno == ENOBUFS) return CanStatus::kWouldBlock;
    ++stats_.errors;
    if (errno == ENETDOWN || errno == ENXIO) state_ = BusState::kDown;
    return CanStatus::kIoError;
  }
  *sent = static_cast<size_t>(r);
  return *sent == count ? CanStatus::kOk : CanStatus::kWouldBlock;
}

void SocketCanBus::on_error_frame(uint32_t err_class, const uint8_t* data) {
  ++stats_.errors;
  if (err_class & CAN_ERR_BUSOFF) {
    if (state_ != BusState::kBusOff) ++stats_.bus_off_events;
    state_ = BusState::kBusOff;
  } else if (err_class & CAN_ERR_RESTARTED) {
    state_ = BusState::kErrorActive;
  } else if (err_class & CAN_ERR_CRTL) {
    const uint8_t c = data[1];
    if (c & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) {
      state_ = BusState::kErrorPassive;
    } else if (c & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) {
      state_ = BusState::kErrorWarning;
    } else if (c & CAN_ERR_CRTL_ACTIVE) {
      state_ = BusState::kErrorActive;
    }
  }
}

bool SocketCanBus::decode(const msghdr& header, const uint8_t* data, size_t size, CanFrame* out) {
  auto* h = const_cast<msghdr*>(&header);  // the CMSG_* macros take non-const pointers
  for (cmsghdr* c = CMSG_FIRSTHDR(h); c != nullptr; c = CMSG_NXTHDR(h, c)) {
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
      uint32_t dropped = 0;
      std::memcpy(&dropped, CMSG_DATA(c), sizeof(dropped));
      stats_.rx_dropped = dropped;  // the kernel's running total for this socket
    }
  }
  const bool is_fd = size == CANFD_MTU;
  if (!is_fd && size != CAN_MTU) {
    ++stats_.errors;
    return false;
  }
  canfd_frame k;
  std::memcpy(&k, data, size);
  if (k.can_id & CAN_ERR_FLAG) {
    on_error_frame(k.can_id & CAN_ERR_MASK, k.data);
    if (!options_.error_frames) return false;
  }
  CanFrame& f = *out;
  if (k.can_id & CAN_ERR_FLAG) {
    f.id = k.can_id & CAN_ERR_MASK;
    f.flags = kFlagError;
    f.len = std::min<uint8_t>(k.len, kClassicMaxLen);
  } else {
    const bool ext = (k.can_id & CAN_EFF_FLAG) != 0;
    f.id = k.can_id & (ext ? CAN_EFF_MASK : CAN_SFF_MASK);
    f.flags = static_cast<uint8_t>(
        (ext ? kFlagExtended : 0) | ((k.can_id & CAN_RTR_FLAG) ? kFlagRemote : 0) |
        (is_fd ? kFlagFd : 0) | ((is_fd && (k.flags & CANFD_BRS)) ? kFlagBrs : 0) |
        ((is_fd && (k.flags & CANFD_ESI)) ? kFlagEsi : 0));
    f.len = std::min<uint8_t>(k.len, is_fd ? kFdMaxLen : kClassicMaxLen);
  }
  std::memcpy(f.data, k.data, f.len);
  return true;
}

CanStatus SocketCanBus::set_filters(const CanFilter* filters, size_t count) {
  if (count > kMaxFilters) return CanStatus::kTooManyFilters;
  can_filter k[kMaxFilters];
  for (size_t i = 0; i < count; ++i) {
    const CanFilter& f = filters[i];
    k[i].can_id = f.id & CAN_EFF_MASK;
    k[i].can_mask = f.mask & CAN_EFF_MASK;
    if (f.type != IdType::kAny) {
      k[i].can_mask |= CAN_EFF_FLAG;
      if (f.type == IdType::kExtended) k[i].can_id |= CAN_EFF_FLAG;
    }
  }
  if (count == 0) {  // accept all
    k[0].can_id = 0;
    k[0].can_mask = 0;
    count = 1;
  }
  if (::setsockopt(fd(), SOL_CAN_RAW, CAN_RAW_FILTER, k,
                   static_cast<socklen_t>(sizeof(can_filter) * count)) < 0) {
    ++stats_.errors;
    return CanStatus::kIoError;
  }
  return CanStatus::kOk;
}

}  // namespace curio::hal
