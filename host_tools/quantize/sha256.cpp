#include "host_tools/quantize/sha256.hpp"

static_assert(SHA256_DIGEST_SIZE == 32, "SHA-256 digests are 32 bytes");

namespace curio::quantize {

Sha256::Sha256() { sha256_init(&ctx_); }

void Sha256::update(std::string_view bytes) {
  sha256_update(&ctx_, bytes.size(), reinterpret_cast<const uint8_t*>(bytes.data()));
}

std::array<uint8_t, 32> Sha256::finish() {
  std::array<uint8_t, 32> digest{};
  sha256_digest(&ctx_, digest.size(), digest.data());
  return digest;
}

std::string to_hex(const std::array<uint8_t, 32>& digest) {
  static const char* kHex = "0123456789abcdef";
  std::string s;
  s.reserve(64);
  for (uint8_t b : digest) {
    s += kHex[b >> 4];
    s += kHex[b & 15];
  }
  return s;
}

std::string sha256_hex(std::string_view bytes) {
  Sha256 h;
  h.update(bytes);
  return to_hex(h.finish());
}

}  // namespace curio::quantize
