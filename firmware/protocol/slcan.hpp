// SLCAN: the ASCII line framing of serial-line CAN (Lawicel CAN232/CANUSB, the kernel's slcan
// driver, slcand, USB-CAN adapters) as pure functions, plus a streaming line assembler with a
// fixed buffer. Firmware-clean: no heap, no OS; the serial port itself is the caller's.
//
// Frame lines (hex digits upper case on output, either case accepted on input):
//   tIIIL<data>\r        classic data frame, 11-bit id (3 digits), L = length 0..8
//   TIIIIIIIIL<data>\r   classic data frame, 29-bit id (8 digits)
//   rIIIL\r  RIIIIIIIIL\r  classic remote request (L = requested length, no data)
//   dIIIL<data>\r  DIIIIIIIIL<data>\r   CAN FD frame without bit-rate switch  } FD extension
//   bIIIL<data>\r  BIIIIIIIIL<data>\r   CAN FD frame with bit-rate switch     } (see below)
// <data> is 2 hex digits per byte. For FD lines L is the DLC as one hex digit 0..F (lengths
// 0..8, 12, 16, 20, 24, 32, 48, 64). A classic line may carry Lawicel's 4-digit timestamp
// after the data (adapter option Z1); it is accepted and ignored.
//
// Classic vs FD. The Lawicel protocol and the Linux kernel's slcan driver (6.1) carry classic
// CAN only: t/T/r/R. The d/D/b/B lines are the FD extension of the CANable 2 / slcan-FD
// adapter firmwares; Curio's arm protocol needs FD for the 48-byte ground truth and the
// 64-byte ISO-TP camera frames, so a link that carries the arm runs in FD mode (only between
// our own endpoints, e.g. the QEMU image and curio-can slcan-bridge). A classic-only link
// (SlcanMode::kClassic) refuses FD frames: they cannot cross the kernel's slcan.
//
// Every other line (adapter commands O, C, S6, V, ..., and the adapter's '\r' / '\a'
// acknowledgements) is reported as kCommand and is not a frame.
#pragma once
#include <cstddef>
#include <cstdint>

#include "hal/can_frame.hpp"

namespace curio::protocol {

using hal::CanFrame;

enum class SlcanMode : uint8_t {
  kClassic = 0,  // t/T/r/R only (Lawicel, the kernel's slcan)
  kFd,           // also d/D/b/B
};

// Longest frame line with its terminator: 'B' + 8 id digits + DLC digit + 128 data digits +
// '\r'. Classic lines are at most 1 + 8 + 1 + 16 + 4 (timestamp) + 1 = 31.
inline constexpr size_t kSlcanMaxLine = 1 + 8 + 1 + 2 * hal::kFdMaxLen + 1;
inline constexpr size_t kSlcanMaxClassicLine = 1 + 8 + 1 + 2 * hal::kClassicMaxLen + 4 + 1;
static_assert(kSlcanMaxLine == 139 && kSlcanMaxClassicLine == 31, "SLCAN line bounds");

enum class SlcanStatus : uint8_t {
  kFrame = 0,    // a frame was decoded
  kPending,      // assembler: line not complete yet
  kCommand,      // a line that is not a frame (adapter command or acknowledgement)
  kBadId,        // id digits missing, not hex, or out of range
  kBadLength,    // length digit invalid, or the data does not match it
  kBadHex,       // a data digit is not hex
  kUnsupported,  // an FD line on a classic-only link
  kOverlong,     // assembler: line longer than kSlcanMaxLine (discarded up to its end)
};

const char* to_string(SlcanStatus s);

// Error and traffic counters of one line assembler.
struct SlcanCounters {
  uint32_t frames = 0;    // frame lines decoded
  uint32_t commands = 0;  // non-frame lines (commands, acknowledgements)
  uint32_t bad_id = 0;
  uint32_t bad_length = 0;
  uint32_t bad_hex = 0;
  uint32_t unsupported = 0;
  uint32_t overlong = 0;
  uint32_t malformed() const { return bad_id + bad_length + bad_hex + unsupported + overlong; }
};

// Bytes of the line for `f` including the '\r', or 0 when it has no SLCAN form in `mode`
// (error frames, FD frames on a classic link, FD frames with ESI, invalid frames).
size_t slcan_line_length(const CanFrame& f, SlcanMode mode);

// Writes the line for `f` (with its '\r', no NUL) into `out`; returns its length, or 0 when
// the frame has no SLCAN form (see slcan_line_length) or `capacity` is too small.
size_t slcan_encode(const CanFrame& f, SlcanMode mode, char* out, size_t capacity);

// Decodes one line (`len` bytes, without the terminator). kFrame fills *out; kCommand for
// non-frame lines; otherwise the reason it is malformed (*out untouched).
SlcanStatus slcan_decode(const char* line, size_t len, SlcanMode mode, CanFrame* out);

// Splits a byte stream into lines at '\r' (also '\n' and '\a', which adapters send) and
// decodes them. Empty lines are skipped. A line longer than kSlcanMaxLine is discarded up to
// its terminator and counted once.
class SlcanLineAssembler {
 public:
  explicit SlcanLineAssembler(SlcanMode mode = SlcanMode::kClassic) : mode_(mode) {}

  // Feeds one byte. kFrame: *out holds the frame of the line that just ended. kPending while
  // a line is incomplete (or was empty); kCommand / an error status when a line ended that
  // is not a frame (counted).
  SlcanStatus push(uint8_t byte, CanFrame* out);

  void reset() {
    used_ = 0;
    discarding_ = false;
  }
  SlcanMode mode() const { return mode_; }
  const SlcanCounters& counters() const { return counters_; }

 private:
  SlcanStatus count(SlcanStatus s);

  SlcanMode mode_;
  char line_[kSlcanMaxLine] = {};
  size_t used_ = 0;
  bool discarding_ = false;  // inside an overlong line
  SlcanCounters counters_;
};

}  // namespace curio::protocol
