// A seed as text, the one reading every program shares: decimal digits only, 0 to
// 2^64 - 1. No sign ("-1" is not 2^64 - 1), no spaces, no "0x", nothing beyond 2^64 - 1
// ("18446744073709551616" is refused, not clamped). Seeds are compared whole everywhere: two
// runs are the same run only if all 64 bits agree.
//
// Used by the --seed options (host_tools/cli/command_line.hpp's kSeed) and by the seed lists of
// curio-lab (host_tools/experiment/campaign_config.hpp's parse_seeds).
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

namespace curio::cli {

inline std::optional<uint64_t> parse_seed(std::string_view text) {
  if (text.empty()) return std::nullopt;
  uint64_t value = 0;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    const auto digit = static_cast<uint64_t>(c - '0');
    if (value > (UINT64_MAX - digit) / 10) return std::nullopt;  // beyond 2^64 - 1
    value = value * 10 + digit;
  }
  return value;
}

}  // namespace curio::cli
