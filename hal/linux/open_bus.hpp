// Bus URLs → backends (options after '?', joined by '&'):
//   loopback | loopback:NAME [?classic=1]       in-process bus (endpoints of one program meet
//                                               by NAME)
//   socketcan:IFACE [?errors=1]                 Linux SocketCAN raw socket (e.g. socketcan:vcan0);
//                                               classic or FD as the interface's MTU says (16/72)
//   udp:127.0.0.1:PORT [?ports=N] [&classic=1]  userspace bus over UDP, ports PORT..PORT+N-1 (N=8)
// classic=1: this endpoint is a classic-only CAN controller (no FD frames), so the arm protocol
// runs its classic profile on it.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "hal/can_bus.hpp"
#include "hal/clock.hpp"

namespace curio::hal {

struct BusUrl {
  enum class Kind { kLoopback, kSocketCan, kUdp };
  Kind kind = Kind::kLoopback;
  std::string name;           // loopback name or network interface
  uint16_t port = 0;          // udp: first port of the range
  unsigned ports = 0;         // udp: size of the range
  bool error_frames = false;  // socketcan: deliver error frames
  bool classic = false;       // loopback, udp: a classic-only endpoint
};

inline constexpr const char* kBusUrlHelp =
    "expected loopback[:NAME][?classic=1], socketcan:IFACE[?errors=1] or "
    "udp:127.0.0.1:PORT[?ports=N][&classic=1]";

// False with *error saying what is wrong with the URL.
bool parse_bus_url(std::string_view url, BusUrl* out, std::string* error);

// Opens an endpoint on the bus named by `url`; null with *error set (bad URL, or the backend
// could not open: no AF_CAN, interface missing, ports taken).
std::unique_ptr<CanBus> open_bus(std::string_view url, std::string* error,
                                 const Clock* clock = nullptr);

}  // namespace curio::hal
