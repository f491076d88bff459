#include "hal/linux/open_bus.hpp"

#include <charconv>

#include "hal/host/loopback_bus.hpp"
#include "hal/linux/socketcan_bus.hpp"
#include "hal/linux/udp_bus.hpp"

namespace curio::hal {
namespace {

bool parse_uint(std::string_view s, unsigned long max, unsigned long* out) {
  if (s.empty()) return false;
  unsigned long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || v > max) return false;
  *out = v;
  return true;
}

bool valid_name(std::string_view s, size_t max_len) {
  if (s.empty() || s.size() > max_len) return false;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

// Splits "a=1&b=2" into options; false when one is not key=value or a key repeats.
struct UrlOption {
  std::string_view key, value;
};
bool split_query(std::string_view query, UrlOption* out, size_t capacity, size_t* count) {
  *count = 0;
  while (!query.empty()) {
    const size_t amp = query.find('&');
    const std::string_view item = query.substr(0, amp);
    const size_t eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0 || *count == capacity) return false;
    const UrlOption o{item.substr(0, eq), item.substr(eq + 1)};
    for (size_t i = 0; i < *count; ++i)
      if (out[i].key == o.key) return false;
    out[(*count)++] = o;
    if (amp == std::string_view::npos) break;
    query = query.substr(amp + 1);
    if (query.empty()) return false;  // a trailing '&'
  }
  return true;
}

// "0" or "1".
bool parse_flag(std::string_view v, bool* out) {
  if (v != "0" && v != "1") return false;
  *out = v == "1";
  return true;
}

}  // namespace

bool parse_bus_url(std::string_view url, BusUrl* out, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error) *error = "bad bus URL '" + std::string(url) + "': " + why + " (" + kBusUrlHelp + ")";
    return false;
  };
  BusUrl u;
  std::string_view query;
  if (const size_t q = url.find('?'); q != std::string_view::npos) {
    query = url.substr(q + 1);
    url = url.substr(0, q);
  }
  UrlOption options[4];
  size_t n_options = 0;
  if (!split_query(query, options, 4, &n_options)) {
    return fail("options must be KEY=VALUE joined by '&', each key once");
  }
  const size_t colon = url.find(':');
  const std::string_view scheme = url.substr(0, colon);
  const std::string_view rest = colon == std::string_view::npos ? "" : url.substr(colon + 1);
  if (scheme == "loopback") {
    u.kind = BusUrl::Kind::kLoopback;
    if (colon == std::string_view::npos) {
      u.name = "default";
    } else if (!valid_name(rest, 64)) {
      return fail("loopback name must be 1-64 characters [A-Za-z0-9_.-]");
    } else {
      u.name = rest;
    }
    for (size_t i = 0; i < n_options; ++i) {
      if (options[i].key != "classic" || !parse_flag(options[i].value, &u.classic))
        return fail("loopback option must be classic=0 or classic=1");
    }
  } else if (scheme == "socketcan") {
    u.kind = BusUrl::Kind::kSocketCan;
    if (!valid_name(rest, 15)) return fail("interface name must be 1-15 characters [A-Za-z0-9_.-]");
    u.name = rest;
    for (size_t i = 0; i < n_options; ++i) {
      if (options[i].key == "classic") {
        return fail("a socketcan interface is classic or FD by its MTU (ip link set IFACE mtu 16 "
                    "or 72), not by an option");
      }
      if (options[i].key != "errors" || !parse_flag(options[i].value, &u.error_frames))
        return fail("socketcan option must be errors=0 or errors=1");
    }
  } else if (scheme == "udp") {
    u.kind = BusUrl::Kind::kUdp;
    const size_t c = rest.rfind(':');
    if (c == std::string_view::npos) return fail("udp needs 127.0.0.1:PORT");
    if (rest.substr(0, c) != "127.0.0.1") {
      return fail("the udp bus only runs on 127.0.0.1 (never any other address)");
    }
    unsigned long port = 0;
    if (!parse_uint(rest.substr(c + 1), 65535, &port) || port == 0) {
      return fail("PORT must be 1..65535");
    }
    unsigned long ports = kUdpDefaultPorts;
    for (size_t i = 0; i < n_options; ++i) {
      if (options[i].key == "ports") {
        if (!parse_uint(options[i].value, kUdpMaxPorts, &ports) || ports < 2)
          return fail("udp option ports=N needs N in 2.." + std::to_string(kUdpMaxPorts));
      } else if (options[i].key != "classic" || !parse_flag(options[i].value, &u.classic)) {
        return fail("udp options are ports=N and classic=0|1");
      }
    }
    if (port + ports - 1 > 65535) return fail("PORT + ports - 1 exceeds 65535");
    u.port = static_cast<uint16_t>(port);
    u.ports = static_cast<unsigned>(ports);
  } else {
    return fail("unknown scheme '" + std::string(scheme) + "'");
  }
  *out = u;
  return true;
}

std::unique_ptr<CanBus> open_bus(std::string_view url, std::string* error, const Clock* clock) {
  BusUrl u;
  if (!parse_bus_url(url, &u, error)) return nullptr;
  switch (u.kind) {
    case BusUrl::Kind::kLoopback: {
      auto bus = named_loopback_bus(u.name, clock);
      auto ep = bus->open(!u.classic);
      if (!ep && error) *error = "loopback:" + u.name + ": all endpoints in use";
      return ep;
    }
    case BusUrl::Kind::kSocketCan:
      return SocketCanBus::open(u.name, SocketCanOptions{u.error_frames}, error, clock);
    case BusUrl::Kind::kUdp:
      return UdpBus::open(u.port, u.ports, error, clock, !u.classic);
  }
  return nullptr;
}

}  // namespace curio::hal
