// One CAN frame, classic or FD, 11- or 29-bit identifier. Firmware-clean: no heap, no OS
// headers; the same type travels through every bus backend and the protocol codecs.
#pragma once
#include <cstddef>
#include <cstdint>

namespace curio::hal {

inline constexpr uint32_t kStdIdMask = 0x7FFu;       // 11-bit base identifier
inline constexpr uint32_t kExtIdMask = 0x1FFFFFFFu;  // 29-bit extended identifier
inline constexpr uint8_t kClassicMaxLen = 8;
inline constexpr uint8_t kFdMaxLen = 64;

// Frame flag bits (CanFrame::flags).
inline constexpr uint8_t kFlagExtended = 0x01;  // 29-bit identifier
inline constexpr uint8_t kFlagFd = 0x02;        // CAN FD frame format
inline constexpr uint8_t kFlagBrs = 0x04;       // FD bit-rate switch
inline constexpr uint8_t kFlagEsi = 0x08;       // FD error-state indicator (sender passive)
inline constexpr uint8_t kFlagRemote = 0x10;    // classic remote request (no payload)
inline constexpr uint8_t kFlagError = 0x20;     // controller error report (SocketCAN error frame)
inline constexpr uint8_t kAllFlags = 0x3F;

// DLC (4 bits on the wire) ↔ payload length. Classic frames use DLC 0–8; FD adds 9–15 for
// 12, 16, 20, 24, 32, 48, 64 bytes.
inline constexpr uint8_t kDlcToLen[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};

// Payload length for a DLC; DLCs above 15 do not exist (returns 0xFF).
constexpr uint8_t dlc_to_len(uint8_t dlc) {
  return dlc < 16 ? kDlcToLen[dlc] : uint8_t{0xFF};
}

// Smallest DLC whose length holds `len` bytes (the FD padding rule); 0xFF if len > 64.
constexpr uint8_t len_to_dlc(size_t len) {
  for (uint8_t dlc = 0; dlc < 16; ++dlc) {
    if (kDlcToLen[dlc] >= len) return dlc;
  }
  return 0xFF;
}

// Length after padding up to the next valid FD length (0xFF if len > 64).
constexpr uint8_t fd_padded_len(size_t len) {
  const uint8_t dlc = len_to_dlc(len);
  return dlc == 0xFF ? uint8_t{0xFF} : kDlcToLen[dlc];
}

// True when `len` is exactly representable: 0–8 for classic, a DLC length for FD.
constexpr bool is_valid_len(size_t len, bool fd) {
  return fd ? (len <= kFdMaxLen && fd_padded_len(len) == len) : len <= kClassicMaxLen;
}

struct CanFrame {
  uint32_t id = 0;    // identifier without flag bits (11 or 29 bits, see kFlagExtended)
  uint8_t len = 0;    // payload length in bytes (a valid length for the format)
  uint8_t flags = 0;  // kFlag* bits
  uint8_t data[kFdMaxLen] = {};

  constexpr bool extended() const { return (flags & kFlagExtended) != 0; }
  constexpr bool fd() const { return (flags & kFlagFd) != 0; }
  constexpr bool remote() const { return (flags & kFlagRemote) != 0; }
  constexpr bool error() const { return (flags & kFlagError) != 0; }
  constexpr uint8_t dlc() const { return len_to_dlc(len); }
};

static_assert(sizeof(CanFrame) <= 72, "a frame is stored by value in fixed queues");

// Frame validity: identifier fits its width, length valid for the format, flags consistent
// (FD frames carry no remote request; BRS/ESI only on FD frames).
constexpr bool is_valid(const CanFrame& f) {
  if ((f.flags & ~kAllFlags) != 0) return false;
  if (f.error()) return f.len <= kClassicMaxLen && !f.fd();
  if (f.id > (f.extended() ? kExtIdMask : kStdIdMask)) return false;
  if (f.fd()) return !f.remote() && is_valid_len(f.len, true);
  if ((f.flags & (kFlagBrs | kFlagEsi)) != 0) return false;
  return f.len <= kClassicMaxLen;
}

// Builds a frame from a payload, padding FD payloads with `pad` up to the next valid
// length. Returns false (frame untouched) when the payload does not fit the format.
constexpr bool make_frame(CanFrame* out, uint32_t id, bool extended, bool fd,
                          const uint8_t* payload, size_t size, uint8_t pad = 0) {
  if (size > (fd ? kFdMaxLen : kClassicMaxLen)) return false;
  if (id > (extended ? kExtIdMask : kStdIdMask)) return false;
  CanFrame f;
  f.id = id;
  f.flags = static_cast<uint8_t>((extended ? kFlagExtended : 0) | (fd ? (kFlagFd | kFlagBrs) : 0));
  f.len = fd ? fd_padded_len(size) : static_cast<uint8_t>(size);
  for (size_t i = 0; i < size; ++i) f.data[i] = payload[i];
  for (size_t i = size; i < f.len && i < kFdMaxLen; ++i) f.data[i] = pad;
  *out = f;
  return true;
}

// Same identifier, format and payload (bytes beyond len are ignored).
constexpr bool same_frame(const CanFrame& a, const CanFrame& b) {
  if (a.id != b.id || a.len != b.len || a.flags != b.flags) return false;
  for (size_t i = 0; i < a.len && i < kFdMaxLen; ++i) {
    if (a.data[i] != b.data[i]) return false;
  }
  return true;
}

}  // namespace curio::hal
