// SHA-256 (FIPS 180-4) from Debian's nettle library (nettle-dev): the quantizer fingerprints
// its inputs with it so a stale generated header can be detected, and a meta JSON names its
// model by it.
#pragma once
#include <nettle/sha2.h>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace curio::quantize {

class Sha256 {
 public:
  Sha256();
  void update(std::string_view bytes);
  std::array<uint8_t, 32> finish();  // the object is spent afterwards

 private:
  sha256_ctx ctx_;
};

std::string sha256_hex(std::string_view bytes);
std::string to_hex(const std::array<uint8_t, 32>& digest);

}  // namespace curio::quantize
