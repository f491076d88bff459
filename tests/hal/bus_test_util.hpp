// Helpers shared by the bus tests: frame builders, collect-with-timeout, free UDP ports.
#pragma once
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <vector>

#include "hal/can_bus.hpp"

namespace curio::hal::test {

inline CanFrame frame_of(uint32_t id, size_t len, bool fd = false, bool ext = false,
                         uint8_t seed = 0) {
  uint8_t payload[64];
  for (size_t i = 0; i < 64; ++i) payload[i] = static_cast<uint8_t>(seed + 7 * i + 1);
  CanFrame f;
  make_frame(&f, id, ext, fd, payload, len);
  return f;
}

// Receives until `n` frames arrived or `timeout_us` passed without one.
inline std::vector<CanFrame> collect(CanBus& bus, size_t n, uint64_t timeout_us = 1'000'000) {
  std::vector<CanFrame> got;
  CanFrame batch[64];
  while (got.size() < n) {
    size_t k = 0;
    if (bus.receive_wait(batch, 64, &k, timeout_us) != CanStatus::kOk) break;
    got.insert(got.end(), batch, batch + k);
  }
  return got;
}

// A base port whose `count` ports on 127.0.0.1 are free right now, one of `slots` bases
// 16 apart from `first` on (per-process start point, so parallel test processes do not meet
// on one bus).
inline uint16_t free_udp_base(unsigned count, unsigned first = 30000, unsigned slots = 1500) {
  for (unsigned attempt = 0; attempt < 200; ++attempt) {
    const auto base = static_cast<uint16_t>(
        first + ((static_cast<unsigned>(getpid()) * 7919u + attempt * 131u) % slots) * 16u);
    bool all_free = true;
    for (unsigned i = 0; i < count && all_free; ++i) {
      const int fd = socket(AF_INET, SOCK_DGRAM, 0);
      sockaddr_in a{};
      a.sin_family = AF_INET;
      a.sin_port = htons(static_cast<uint16_t>(base + i));
      a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      all_free = bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) == 0;
      close(fd);
    }
    if (all_free) return base;
  }
  return 0;
}

}  // namespace curio::hal::test
