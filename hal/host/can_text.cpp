#include "hal/host/can_text.hpp"

#include <cstdio>

namespace curio::hal {
namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::string format_frame(const CanFrame& f) {
  char buf[8 + 3 + 2 * kFdMaxLen + 1];
  int n = std::snprintf(buf, sizeof(buf), f.extended() ? "%08X" : "%03X", f.id);
  if (f.fd()) {
    const int fd_flags = ((f.flags & kFlagBrs) ? 1 : 0) | ((f.flags & kFlagEsi) ? 2 : 0);
    n += std::snprintf(buf + n, sizeof(buf) - static_cast<size_t>(n), "##%X", fd_flags);
  } else {
    buf[n++] = '#';
    if (f.remote()) buf[n++] = 'R';
  }
  for (size_t i = 0; i < f.len && !f.remote(); ++i) {
    n += std::snprintf(buf + n, sizeof(buf) - static_cast<size_t>(n), "%02X", f.data[i]);
  }
  return std::string(buf, static_cast<size_t>(n));
}

bool parse_frame(std::string_view text, CanFrame* out) {
  const size_t hash = text.find('#');
  if (hash == std::string_view::npos || (hash != 3 && hash != 8)) return false;
  CanFrame f;
  for (size_t i = 0; i < hash; ++i) {
    const int v = hex_value(text[i]);
    if (v < 0) return false;
    f.id = (f.id << 4) | static_cast<uint32_t>(v);
  }
  if (hash == 8) f.flags |= kFlagExtended;
  std::string_view rest = text.substr(hash + 1);
  if (!rest.empty() && rest[0] == '#') {
    if (rest.size() < 2) return false;
    const int fl = hex_value(rest[1]);
    if (fl < 0 || fl > 3) return false;
    f.flags = static_cast<uint8_t>(f.flags | kFlagFd | ((fl & 1) ? kFlagBrs : 0) |
                                   ((fl & 2) ? kFlagEsi : 0));
    rest = rest.substr(2);
  } else if (rest == "R") {
    f.flags |= kFlagRemote;
    rest = {};
  }
  // Dots between bytes are allowed, as in cansend.
  size_t len = 0;
  for (size_t i = 0; i < rest.size();) {
    if (rest[i] == '.') {
      ++i;
      continue;
    }
    if (i + 1 >= rest.size() || len >= kFdMaxLen) return false;
    const int hi = hex_value(rest[i]), lo = hex_value(rest[i + 1]);
    if (hi < 0 || lo < 0) return false;
    f.data[len++] = static_cast<uint8_t>(hi * 16 + lo);
    i += 2;
  }
  f.len = static_cast<uint8_t>(len);
  if (!is_valid(f)) return false;
  *out = f;
  return true;
}

}  // namespace curio::hal
