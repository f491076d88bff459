// SLCAN line encoding, decoding and the streaming line assembler (slcan.hpp).
#include "firmware/protocol/slcan.hpp"

namespace curio::protocol {

namespace {

constexpr char kHex[] = "0123456789ABCDEF";

// 0..15, or -1 for a non-hex character.
int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

struct LineKind {
  bool frame = false;
  bool extended = false;
  bool remote = false;
  bool fd = false;
  bool brs = false;
};

LineKind kind_of(char c) {
  switch (c) {
    case 't':
      return {true, false, false, false, false};
    case 'T':
      return {true, true, false, false, false};
    case 'r':
      return {true, false, true, false, false};
    case 'R':
      return {true, true, true, false, false};
    case 'd':
      return {true, false, false, true, false};
    case 'D':
      return {true, true, false, true, false};
    case 'b':
      return {true, false, false, true, true};
    case 'B':
      return {true, true, false, true, true};
    default:
      return {};
  }
}

bool has_slcan_form(const CanFrame& f, SlcanMode mode) {
  if (!hal::is_valid(f) || f.error()) return false;
  if (!f.fd()) return true;
  return mode == SlcanMode::kFd && (f.flags & hal::kFlagEsi) == 0;
}

}  // namespace

const char* to_string(SlcanStatus s) {
  switch (s) {
    case SlcanStatus::kFrame:
      return "frame";
    case SlcanStatus::kPending:
      return "pending";
    case SlcanStatus::kCommand:
      return "command";
    case SlcanStatus::kBadId:
      return "bad id";
    case SlcanStatus::kBadLength:
      return "bad length";
    case SlcanStatus::kBadHex:
      return "bad hex digit";
    case SlcanStatus::kUnsupported:
      return "FD line on a classic link";
    case SlcanStatus::kOverlong:
      return "overlong line";
  }
  return "?";
}

size_t slcan_line_length(const CanFrame& f, SlcanMode mode) {
  if (!has_slcan_form(f, mode)) return 0;
  const size_t id_digits = f.extended() ? 8 : 3;
  const size_t data_digits = f.remote() ? 0 : 2u * f.len;
  return 1 + id_digits + 1 + data_digits + 1;
}

size_t slcan_encode(const CanFrame& f, SlcanMode mode, char* out, size_t capacity) {
  const size_t n = slcan_line_length(f, mode);
  if (n == 0 || n > capacity) return 0;
  char c = 't';
  if (f.fd()) {
    c = (f.flags & hal::kFlagBrs) != 0 ? 'b' : 'd';
  } else if (f.remote()) {
    c = 'r';
  }
  if (f.extended()) c = static_cast<char>(c - 'a' + 'A');
  size_t at = 0;
  out[at++] = c;
  const int id_digits = f.extended() ? 8 : 3;
  for (int i = id_digits - 1; i >= 0; --i) out[at++] = kHex[(f.id >> (4 * i)) & 0xFu];
  out[at++] = kHex[f.fd() ? f.dlc() : f.len];
  if (!f.remote()) {
    for (size_t i = 0; i < f.len; ++i) {
      out[at++] = kHex[f.data[i] >> 4];
      out[at++] = kHex[f.data[i] & 0xFu];
    }
  }
  out[at++] = '\r';
  return at;
}

SlcanStatus slcan_decode(const char* line, size_t len, SlcanMode mode, CanFrame* out) {
  if (len == 0) return SlcanStatus::kCommand;
  const LineKind k = kind_of(line[0]);
  if (!k.frame) return SlcanStatus::kCommand;
  if (k.fd && mode != SlcanMode::kFd) return SlcanStatus::kUnsupported;

  const size_t id_digits = k.extended ? 8 : 3;
  if (len < 1 + id_digits) return SlcanStatus::kBadId;
  uint32_t id = 0;
  for (size_t i = 1; i <= id_digits; ++i) {
    const int v = hex_value(line[i]);
    if (v < 0) return SlcanStatus::kBadId;
    id = (id << 4) | static_cast<uint32_t>(v);
  }
  if (id > (k.extended ? hal::kExtIdMask : hal::kStdIdMask)) return SlcanStatus::kBadId;

  size_t at = 1 + id_digits;
  if (at >= len) return SlcanStatus::kBadLength;
  const int l = hex_value(line[at++]);
  if (l < 0) return SlcanStatus::kBadLength;
  size_t payload = 0;
  if (k.fd) {
    payload = hal::dlc_to_len(static_cast<uint8_t>(l));
  } else {
    if (l > hal::kClassicMaxLen) return SlcanStatus::kBadLength;
    payload = static_cast<size_t>(l);
  }
  const size_t data_digits = k.remote ? 0 : 2 * payload;
  const size_t rest = len - at;
  // Classic lines may end in a 4-digit timestamp (Lawicel Z1), checked as hex and ignored.
  const bool stamped = !k.fd && rest == data_digits + 4;
  if (rest != data_digits && !stamped) return SlcanStatus::kBadLength;

  CanFrame f;
  f.id = id;
  f.len = static_cast<uint8_t>(payload);
  f.flags = static_cast<uint8_t>((k.extended ? hal::kFlagExtended : 0) |
                                 (k.remote ? hal::kFlagRemote : 0) | (k.fd ? hal::kFlagFd : 0) |
                                 (k.brs ? hal::kFlagBrs : 0));
  for (size_t i = 0; i < data_digits / 2; ++i) {
    const int hi = hex_value(line[at + 2 * i]);
    const int lo = hex_value(line[at + 2 * i + 1]);
    if (hi < 0 || lo < 0) return SlcanStatus::kBadHex;
    f.data[i] = static_cast<uint8_t>((hi << 4) | lo);
  }
  if (stamped) {
    for (size_t i = at + data_digits; i < len; ++i) {
      if (hex_value(line[i]) < 0) return SlcanStatus::kBadHex;
    }
  }
  *out = f;
  return SlcanStatus::kFrame;
}

SlcanStatus SlcanLineAssembler::count(SlcanStatus s) {
  switch (s) {
    case SlcanStatus::kFrame:
      ++counters_.frames;
      break;
    case SlcanStatus::kCommand:
      ++counters_.commands;
      break;
    case SlcanStatus::kBadId:
      ++counters_.bad_id;
      break;
    case SlcanStatus::kBadLength:
      ++counters_.bad_length;
      break;
    case SlcanStatus::kBadHex:
      ++counters_.bad_hex;
      break;
    case SlcanStatus::kUnsupported:
      ++counters_.unsupported;
      break;
    case SlcanStatus::kOverlong:
      ++counters_.overlong;
      break;
    case SlcanStatus::kPending:
      break;
  }
  return s;
}

SlcanStatus SlcanLineAssembler::push(uint8_t byte, CanFrame* out) {
  const bool end = byte == '\r' || byte == '\n' || byte == '\a';
  if (!end) {
    if (discarding_) return SlcanStatus::kPending;
    if (used_ == sizeof line_) {  // no line is this long: drop it up to its end
      discarding_ = true;
      used_ = 0;
      return count(SlcanStatus::kOverlong);
    }
    line_[used_++] = static_cast<char>(byte);
    return SlcanStatus::kPending;
  }
  if (discarding_) {
    discarding_ = false;
    return SlcanStatus::kPending;
  }
  const size_t n = used_;
  used_ = 0;
  // An empty line is the adapter's acknowledgement of a command ('\r' alone) or a '\n' after
  // a '\r': nothing to report. A lone '\a' is the adapter's error reply.
  if (n == 0) return byte == '\a' ? count(SlcanStatus::kCommand) : SlcanStatus::kPending;
  return count(slcan_decode(line_, n, mode_, out));
}

}  // namespace curio::protocol
