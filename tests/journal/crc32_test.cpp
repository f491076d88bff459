// CRC-32 (firmware/journal/crc32.hpp) against the standard check values (zlib's crc32()).
#include "firmware/journal/crc32.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace curio::journal {
namespace {

uint32_t crc_of(const char* s) {
  return crc32(reinterpret_cast<const uint8_t*>(s), std::strlen(s));
}

TEST(Crc32, StandardVectors) {
  EXPECT_EQ(crc_of(""), 0x00000000u);
  EXPECT_EQ(crc_of("a"), 0xE8B7BE43u);
  EXPECT_EQ(crc_of("123456789"), 0xCBF43926u);
  EXPECT_EQ(crc_of("The quick brown fox jumps over the lazy dog"), 0x414FA339u);
  const uint8_t zeros[32] = {};
  EXPECT_EQ(crc32(zeros, sizeof zeros), 0x190A55ADu);
  uint8_t ff[32];
  std::memset(ff, 0xFF, sizeof ff);
  EXPECT_EQ(crc32(ff, sizeof ff), 0xFF6CAB0Bu);
}

TEST(Crc32, IncrementalEqualsOneShot) {
  const char* s = "The quick brown fox jumps over the lazy dog";
  const auto* p = reinterpret_cast<const uint8_t*>(s);
  const size_t n = std::strlen(s);
  for (size_t cut = 0; cut <= n; ++cut)
    EXPECT_EQ(crc32_final(crc32_update(crc32_update(kCrc32Init, p, cut), p + cut, n - cut)),
              crc32(p, n))
        << "split at " << cut;
}

TEST(Crc32, EverySingleBitFlipChangesIt) {
  uint8_t buf[64];
  for (size_t i = 0; i < sizeof buf; ++i) buf[i] = static_cast<uint8_t>(i * 37 + 11);
  const uint32_t good = crc32(buf, sizeof buf);
  for (size_t i = 0; i < sizeof buf; ++i)
    for (int b = 0; b < 8; ++b) {
      buf[i] ^= static_cast<uint8_t>(1u << b);
      EXPECT_NE(crc32(buf, sizeof buf), good) << "byte " << i << " bit " << b;
      buf[i] ^= static_cast<uint8_t>(1u << b);
    }
}

}  // namespace
}  // namespace curio::journal
