// CRC-32 (IEEE 802.3 / zlib / PNG: reflected polynomial 0xEDB88320, init and final XOR
// 0xFFFFFFFF) with a 16-entry nibble table: 64 bytes of flash, two lookups per byte.
// Check value: crc32("123456789") = 0xCBF43926 (tests/journal/crc32_test.cpp has more vectors).
// Incremental: crc32_update(crc32_update(kCrc32Init, a), b) then crc32_final() equals the CRC
// of a followed by b.
#pragma once
#include <cstddef>
#include <cstdint>

namespace curio::journal {

inline constexpr uint32_t kCrc32Init = 0xFFFFFFFFu;

namespace detail {
constexpr uint32_t crc32_nibble(uint32_t n) {
  uint32_t c = n;
  for (int k = 0; k < 4; ++k) c = (c & 1u) ? (c >> 1) ^ 0xEDB88320u : c >> 1;
  return c;
}
inline constexpr uint32_t kCrc32Nibbles[16] = {
    crc32_nibble(0),  crc32_nibble(1),  crc32_nibble(2),  crc32_nibble(3),
    crc32_nibble(4),  crc32_nibble(5),  crc32_nibble(6),  crc32_nibble(7),
    crc32_nibble(8),  crc32_nibble(9),  crc32_nibble(10), crc32_nibble(11),
    crc32_nibble(12), crc32_nibble(13), crc32_nibble(14), crc32_nibble(15)};
}  // namespace detail

// Running CRC state (start from kCrc32Init), not yet inverted.
constexpr uint32_t crc32_update(uint32_t state, const uint8_t* data, size_t len) {
  for (size_t i = 0; i < len; ++i) {
    state ^= data[i];
    state = (state >> 4) ^ detail::kCrc32Nibbles[state & 0xFu];
    state = (state >> 4) ^ detail::kCrc32Nibbles[state & 0xFu];
  }
  return state;
}
constexpr uint32_t crc32_final(uint32_t state) { return state ^ 0xFFFFFFFFu; }
constexpr uint32_t crc32(const uint8_t* data, size_t len) {
  return crc32_final(crc32_update(kCrc32Init, data, len));
}

namespace detail {
constexpr uint8_t kCheck[9] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
}
static_assert(crc32(detail::kCheck, 9) == 0xCBF43926u, "CRC-32 check value");

}  // namespace curio::journal
