// SHA-256 (FIPS 180-4), small and dependency-free: the quantizer fingerprints its inputs
// with it so a stale generated header can be detected.
#pragma once
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
  void block(const uint8_t* p);
  std::array<uint32_t, 8> h_;
  std::array<uint8_t, 64> buf_{};
  size_t buf_len_ = 0;
  uint64_t total_ = 0;
};

std::string sha256_hex(std::string_view bytes);
std::string to_hex(const std::array<uint8_t, 32>& digest);

}  // namespace curio::quantize
