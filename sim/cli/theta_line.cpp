#include "sim/cli/theta_line.hpp"

#include <cmath>
#include <cstdlib>
#include <string>

namespace curio::sim {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}
bool is_separator(char c) {
  return is_space(c) || c == ',';
}

// Whole token as a double (C locale strtod: decimal, exponent, inf/nan spelled out).
// Overflow comes back as ±inf and underflow as a tiny value, both judged by the caller.
bool parse_number(std::string_view token, double* value) {
  const std::string text(token);
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && !is_space(text.front());
}

// Control characters (escape sequences, bells, backspaces) as \xNN: a message never moves the
// terminal's cursor or changes its colours.
std::string printable(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7F) {
      out += c;
    } else {
      out.append("\\x").push_back(kHex[u >> 4]);
      out.push_back(kHex[u & 0xF]);
    }
  }
  return out;
}

// A token as quoted in a message: whole if short, else its first kEchoBytes bytes (cut on a
// UTF-8 character boundary) and its size, so a 10 MB token is not echoed back whole.
constexpr size_t kEchoBytes = 40;
std::string echo(std::string_view token) {
  if (token.size() <= kEchoBytes) return printable(token);
  size_t n = kEchoBytes;
  while (n > 0 && (static_cast<unsigned char>(token[n]) & 0xC0) == 0x80) --n;
  return printable(token.substr(0, n)) + "… (" + std::to_string(token.size()) + " bytes)";
}

}  // namespace

ThetaLineStatus parse_theta_line(std::string_view line, float theta[kThetaDim],
                                 std::string* error) {
  size_t pos = 0;
  while (pos < line.size() && is_space(line[pos])) ++pos;
  if (pos == line.size() || line[pos] == '#') return ThetaLineStatus::kSkip;

  int count = 0;
  bool value_since_comma = false;  // rejects ",," and a leading comma
  while (pos < line.size()) {
    const char c = line[pos];
    if (is_space(c)) {
      ++pos;
      continue;
    }
    if (c == ',') {
      if (!value_since_comma) {
        *error = "empty value before comma at column " + std::to_string(pos + 1);
        return ThetaLineStatus::kError;
      }
      value_since_comma = false;
      ++pos;
      continue;
    }
    const size_t start = pos;
    while (pos < line.size() && !is_separator(line[pos])) ++pos;
    const std::string_view token = line.substr(start, pos - start);
    ++count;
    value_since_comma = true;
    double value = 0.0;
    if (!parse_number(token, &value)) {
      *error = "value " + std::to_string(count) + " ('" + echo(token) + "') is not a number";
      return ThetaLineStatus::kError;
    }
    if (!std::isfinite(value)) {
      *error = "value " + std::to_string(count) + " ('" + echo(token) + "') is not finite";
      return ThetaLineStatus::kError;
    }
    if (value < -1.0 || value > 1.0) {
      *error = "value " + std::to_string(count) + " (" + echo(token) + ") is outside [-1, 1]";
      return ThetaLineStatus::kError;
    }
    if (count <= kThetaDim) theta[count - 1] = static_cast<float>(value);
  }
  if (!value_since_comma) {
    *error = "trailing comma";
    return ThetaLineStatus::kError;
  }
  if (count != kThetaDim) {
    *error = "expected " + std::to_string(kThetaDim) + " numbers, got " + std::to_string(count);
    return ThetaLineStatus::kError;
  }
  return ThetaLineStatus::kTheta;
}

}  // namespace curio::sim
