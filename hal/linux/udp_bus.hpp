// Userspace multi-process CAN bus over UDP on 127.0.0.1 (URL `udp:127.0.0.1:PORT`). Not
// SocketCAN and no kernel CAN involved: it exists so several processes (simulator, controller,
// tools) can share one bus on a kernel without AF_CAN.
//
// Design (no hub process): the bus is the port range [PORT, PORT + ports). Each endpoint binds
// the first free port of the range on 127.0.0.1 and sends every frame as one datagram to each
// other live port of the range, all in one sendmmsg() call. Liveness without a handshake: a
// frame to an unbound port comes back as an ICMP "port unreachable" (read with IP_RECVERR),
// which marks that port dead for kUdpDeadProbeUs, after which it is tried again (sending to
// dead ports costs the kernel an ICMP each: a 7x slowdown if never skipped). A joining
// endpoint announces itself with a hello datagram and a closing one says bye; peers act on
// them when they next read. So a peer that joins may miss up to kUdpDeadProbeUs of frames
// from an endpoint that sends without reading; endpoints that read learn at once. Per-sender order
// is preserved (loopback UDP is FIFO); frames of different senders interleave in arrival order.
// Datagrams from any other address or port are dropped and counted as errors. An endpoint
// opened classic (carries_fd false, URL option classic=1) behaves as a classic-only CAN
// controller: it refuses to send FD frames and drops FD frames it receives (counted as errors).
// Datagram format
// (little-endian):
//   byte 0 kind: 'C' (0x43) frame, 'H' hello, 'B' bye; byte 1 version 1;
//   byte 2 CanFrame::flags, byte 3 length, bytes 4..7 identifier, then `length` payload bytes
//   (hello/bye: 8 bytes, zero fields).
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "hal/linux/socket_bus.hpp"

namespace curio::hal {

inline constexpr uint8_t kUdpMagic = 0x43;
inline constexpr uint8_t kUdpVersion = 1;
inline constexpr size_t kUdpHeaderBytes = 8;
inline constexpr unsigned kUdpDefaultPorts = 8;
inline constexpr unsigned kUdpMaxPorts = 16;
inline constexpr uint64_t kUdpDeadProbeUs = 100'000;

// Datagram codec (exposed for tests and the fuzzer). encode returns the datagram size.
size_t encode_udp_datagram(const CanFrame& frame, uint8_t* out /* kUdpHeaderBytes + 64 */);
bool decode_udp_datagram(const uint8_t* data, size_t size, CanFrame* out);

class UdpBus final : public SocketBus {
 public:
  // Joins the bus [base_port, base_port + ports) on 127.0.0.1; null with *error set when every
  // port of the range is taken or the arguments are bad.
  static std::unique_ptr<UdpBus> open(uint16_t base_port, unsigned ports, std::string* error,
                                      const Clock* clock = nullptr, bool carries_fd = true);
  ~UdpBus() override;  // says bye

  CanStatus set_filters(const CanFilter* filters, size_t count) override;

  uint16_t port() const { return port_; }
  bool carries_fd() const override { return carries_fd_; }

 protected:
  CanStatus transmit(const CanFrame* frames, size_t count, size_t* sent) override;
  bool supports(const CanFrame& frame) const override { return carries_fd_ || !frame.fd(); }
  // A frame datagram from a peer of the bus (hello/bye update its liveness; foreign or
  // malformed datagrams count as errors; the software filters apply).
  bool decode(const msghdr& header, const uint8_t* data, size_t size, CanFrame* out) override;
  // ECONNREFUSED: a queued ICMP error; learn the dead port and read again.
  bool recover(int err) override;
  // POLLERR: ICMP errors are queued; take them, go on waiting.
  bool on_poll_error() override;

 private:
  UdpBus(int fd, uint16_t base_port, unsigned ports, uint16_t port, const Clock* clock,
         bool carries_fd);
  // Sends a header-only control datagram ('H' or 'B') to every other port.
  void announce(uint8_t kind);
  // Reads ICMP errors queued by IP_RECVERR and marks their ports dead.
  void drain_error_queue();

  uint16_t base_port_;
  unsigned ports_;
  uint16_t port_;
  bool carries_fd_;
  uint64_t dead_until_us_[kUdpMaxPorts] = {};  // per port index; 0 = presumed alive
  CanFilter filters_[kMaxFilters] = {};
  size_t filter_count_ = 0;
};

}  // namespace curio::hal
