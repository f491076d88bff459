// The ZynqMP CAN controller (Xilinx UG1085 ch. 20, register reference UG1087 "CAN"): its
// register map and the pure parts of its driver (bit timing, the frame's four FIFO words, the
// acceptance filters, the error state), constexpr and free of register access, so the host
// tests them (tests/hal/zynqmp_can_codec_test.cpp) and the driver (zynqmp_can.hpp) uses them.
// Firmware-clean: no heap, no OS headers.
#pragma once
#include <cstddef>
#include <cstdint>

#include "hal/can_bus.hpp"
#include "hal/can_frame.hpp"

namespace curio::hal::zynqmp {

// Register offsets (UG1087) and the bits the driver uses.
namespace can_reg {
inline constexpr uint32_t kSrr = 0x00;   // software reset: SRST bit 0, CEN bit 1
inline constexpr uint32_t kMsr = 0x04;   // mode select: SLEEP 0, LBACK 1, SNOOP 2
inline constexpr uint32_t kBrpr = 0x08;  // baud rate prescaler: BRP [7:0], tq = (BRP+1)/f_ref
inline constexpr uint32_t kBtr = 0x0C;   // bit timing: TS1 [3:0], TS2 [6:4], SJW [8:7] (each +1)
inline constexpr uint32_t kEcr = 0x10;   // error counters: TEC [7:0], REC [15:8]
inline constexpr uint32_t kEsr =
    0x14;  // error status (write 1 to clear): CRC, FMER, STER, BERR, ACKER
inline constexpr uint32_t kSr = 0x18;        // status
inline constexpr uint32_t kIsr = 0x1C;       // interrupt status
inline constexpr uint32_t kIer = 0x20;       // interrupt enable
inline constexpr uint32_t kIcr = 0x24;       // interrupt clear
inline constexpr uint32_t kTcr = 0x28;       // timestamp control
inline constexpr uint32_t kWir = 0x2C;       // watermarks: FW [7:0], EW [15:8]
inline constexpr uint32_t kTxFifoId = 0x30;  // TX FIFO: ID, DLC, DW1, DW2 (DW2 queues the frame)
inline constexpr uint32_t kRxFifoId = 0x50;  // RX FIFO: ID, DLC, DW1, DW2
inline constexpr uint32_t kAfr = 0x60;       // acceptance filter enables UAF1..UAF4 (bits 0..3)
inline constexpr uint32_t kAfmr1 = 0x64;     // filter n mask: 0x64 + 8(n-1); id: 0x68 + 8(n-1)
inline constexpr uint32_t kAfir1 = 0x68;

inline constexpr uint32_t kSrrSrst = 1u << 0;
inline constexpr uint32_t kSrrCen = 1u << 1;
inline constexpr uint32_t kMsrLback = 1u << 1;
inline constexpr uint32_t kSrConfig = 1u << 0;
inline constexpr uint32_t kSrErrWrn = 1u << 6;
inline constexpr uint32_t kSrEstatShift = 7;  // 2 bits: 00 config, 01 active, 11 passive, 10 off
inline constexpr uint32_t kSrTxFll = 1u << 10;
inline constexpr uint32_t kSrAcfBsy = 1u << 11;
// ISR / IER / ICR bits
inline constexpr uint32_t kIrqArbLst = 1u << 0;
inline constexpr uint32_t kIrqTxOk = 1u << 1;
inline constexpr uint32_t kIrqTxFll = 1u << 2;
inline constexpr uint32_t kIrqRxOk = 1u << 4;
inline constexpr uint32_t kIrqRxUflw = 1u << 5;
inline constexpr uint32_t kIrqRxOflw = 1u << 6;
inline constexpr uint32_t kIrqRxNemp = 1u << 7;
inline constexpr uint32_t kIrqError = 1u << 8;
inline constexpr uint32_t kIrqBsOff = 1u << 9;
inline constexpr uint32_t kIrqTxFemp = 1u << 14;
}  // namespace can_reg

inline constexpr size_t kHwFilters = 4;  // UAF1..UAF4
inline constexpr size_t kHwTxFifo = 64;  // frames the TX FIFO holds
inline constexpr size_t kHwRxFifo = 64;  // frames the RX FIFO holds

// ---------------------------------------------------------------- bit timing
// Nominal bit = sync (1 tq) + TS1 (1..16 tq) + TS2 (1..8 tq), tq = BRP/f_ref with BRP 1..256.
struct CanBitTiming {
  uint16_t brp = 0;  // prescaler (register value + 1)
  uint8_t ts1 = 0;   // tq (register value + 1)
  uint8_t ts2 = 0;   // tq
  uint8_t sjw = 0;   // tq
  uint16_t sample_point_permille = 0;
  constexpr uint32_t tq_per_bit() const { return 1u + ts1 + ts2; }
  constexpr uint32_t brpr_value() const { return brp - 1u; }
  constexpr uint32_t btr_value() const {
    return (static_cast<uint32_t>(ts1) - 1u) | ((static_cast<uint32_t>(ts2) - 1u) << 4) |
           ((static_cast<uint32_t>(sjw) - 1u) << 7);
  }
};

// Timing for exactly `bitrate` bit/s from the reference clock, with the sample point nearest
// `sample_point_permille` (CiA 301 recommends 875); among equally near ones, the most time
// quanta per bit. False, *out untouched, when no prescaler divides the clock into a whole
// number of 8..25 quanta per bit (the bitrate cannot be met exactly: refused, never rounded).
constexpr bool compute_bit_timing(uint32_t ref_clock_hz, uint32_t bitrate,
                                  uint16_t sample_point_permille, CanBitTiming* out) {
  if (bitrate == 0 || ref_clock_hz == 0 || sample_point_permille >= 1000) return false;
  bool found = false;
  CanBitTiming best;
  uint32_t best_err = 0xFFFFFFFFu;
  for (uint32_t tq = 25; tq >= 8; --tq) {
    const uint64_t per_bit = static_cast<uint64_t>(bitrate) * tq;
    if (ref_clock_hz % per_bit != 0) continue;
    const uint64_t brp = ref_clock_hz / per_bit;
    if (brp < 1 || brp > 256) continue;
    // Sample point after sync + TS1: choose TS1 nearest the wanted point, within 1..16 and
    // leaving TS2 in 1..8.
    for (uint32_t ts2 = 1; ts2 <= 8; ++ts2) {
      if (tq < 2 + ts2) continue;
      const uint32_t ts1 = tq - 1 - ts2;
      if (ts1 < 1 || ts1 > 16) continue;
      const uint32_t sp = (1000u * (1u + ts1)) / tq;
      const uint32_t err =
          sp > sample_point_permille ? sp - sample_point_permille : sample_point_permille - sp;
      if (err < best_err) {
        best_err = err;
        best.brp = static_cast<uint16_t>(brp);
        best.ts1 = static_cast<uint8_t>(ts1);
        best.ts2 = static_cast<uint8_t>(ts2);
        best.sjw = static_cast<uint8_t>(ts2 < 4 ? ts2 : 4);
        best.sample_point_permille = static_cast<uint16_t>(sp);
        found = true;
      }
    }
  }
  if (found) *out = best;
  return found;
}

// ---------------------------------------------------------------- frame words
// Each frame in a FIFO is four 32-bit words: ID, DLC, DW1, DW2.
//   kUg1085 (the chip, UG1087): ID = IDH[31:21] SRR[20] IDE[19] IDL[18:1] RTR[0]; a standard
//     frame's identifier is IDH, its RTR is SRR; an extended one's is IDH:IDL (11 + 18 bits)
//     with SRR = 1 (recessive), IDE = 1, RTR = its remote flag. DLC = DLC[31:28] (RX: the
//     timestamp in [15:0]). DW1 = bytes 0..3 with byte 0 in [31:24]; DW2 = bytes 4..7.
//   kQemu72 (QEMU 7.2's model): the model hands its ID word to the QEMU CAN bus as a
//     SocketCAN can_id (bit 31 extended, bit 30 remote, identifier in [28:0]) and its data
//     words as little-endian bytes (byte 0 in [7:0]); between two modelled controllers either
//     layout round-trips, but only this one reaches Linux intact through can-host-socketcan
//     (docs/deploy.md lists this departure from the chip).
enum class FrameWordLayout : uint8_t { kUg1085 = 0, kQemu72 };

struct FrameWords {
  uint32_t id = 0;
  uint32_t dlc = 0;
  uint32_t dw1 = 0;
  uint32_t dw2 = 0;
};

inline constexpr uint32_t kQemuEff = 1u << 31;
inline constexpr uint32_t kQemuRtr = 1u << 30;

// The controller is CAN 2.0B: classic data and remote frames only. False for FD or error
// frames and for invalid ones.
constexpr bool encode_frame(const CanFrame& f, FrameWordLayout layout, FrameWords* w) {
  if (!is_valid(f) || f.fd() || f.error()) return false;
  FrameWords out;
  if (layout == FrameWordLayout::kUg1085) {
    if (f.extended()) {
      out.id = ((f.id >> 18) & 0x7FFu) << 21 | 1u << 20 | 1u << 19 | (f.id & 0x3FFFFu) << 1 |
               (f.remote() ? 1u : 0u);
    } else {
      out.id = (f.id & 0x7FFu) << 21 | (f.remote() ? 1u << 20 : 0u);
    }
  } else {
    out.id = f.id | (f.extended() ? kQemuEff : 0u) | (f.remote() ? kQemuRtr : 0u);
  }
  out.dlc = static_cast<uint32_t>(f.len) << 28;
  uint8_t b[8] = {};
  if (!f.remote()) {
    for (size_t i = 0; i < f.len; ++i) b[i] = f.data[i];
  }
  if (layout == FrameWordLayout::kUg1085) {
    out.dw1 = static_cast<uint32_t>(b[0]) << 24 | static_cast<uint32_t>(b[1]) << 16 |
              static_cast<uint32_t>(b[2]) << 8 | b[3];
    out.dw2 = static_cast<uint32_t>(b[4]) << 24 | static_cast<uint32_t>(b[5]) << 16 |
              static_cast<uint32_t>(b[6]) << 8 | b[7];
  } else {
    out.dw1 = static_cast<uint32_t>(b[3]) << 24 | static_cast<uint32_t>(b[2]) << 16 |
              static_cast<uint32_t>(b[1]) << 8 | b[0];
    out.dw2 = static_cast<uint32_t>(b[7]) << 24 | static_cast<uint32_t>(b[6]) << 16 |
              static_cast<uint32_t>(b[5]) << 8 | b[4];
  }
  *w = out;
  return true;
}

// False for words no CAN 2.0B frame encodes to (a length over 8, a SocketCAN error flag).
constexpr bool decode_frame(const FrameWords& w, FrameWordLayout layout, CanFrame* f) {
  CanFrame out;
  const uint32_t dlc = w.dlc >> 28;
  if (dlc > 8) return false;
  out.len = static_cast<uint8_t>(dlc);
  bool remote = false;
  if (layout == FrameWordLayout::kUg1085) {
    const bool ide = (w.id >> 19 & 1u) != 0;
    if (ide) {
      out.id = ((w.id >> 21) & 0x7FFu) << 18 | ((w.id >> 1) & 0x3FFFFu);
      out.flags = kFlagExtended;
      remote = (w.id & 1u) != 0;
    } else {
      out.id = (w.id >> 21) & 0x7FFu;
      remote = (w.id >> 20 & 1u) != 0;
    }
  } else {
    if ((w.id & (1u << 29)) != 0) return false;  // a SocketCAN error frame
    const bool eff = (w.id & kQemuEff) != 0;
    out.id = w.id & (eff ? kExtIdMask : kStdIdMask);
    if (eff) out.flags = kFlagExtended;
    remote = (w.id & kQemuRtr) != 0;
  }
  if (remote) {
    out.flags = static_cast<uint8_t>(out.flags | kFlagRemote);
  } else {
    uint8_t b[8] = {};
    if (layout == FrameWordLayout::kUg1085) {
      for (int i = 0; i < 4; ++i) {
        b[i] = static_cast<uint8_t>(w.dw1 >> (24 - 8 * i));
        b[4 + i] = static_cast<uint8_t>(w.dw2 >> (24 - 8 * i));
      }
    } else {
      for (int i = 0; i < 4; ++i) {
        b[i] = static_cast<uint8_t>(w.dw1 >> (8 * i));
        b[4 + i] = static_cast<uint8_t>(w.dw2 >> (8 * i));
      }
    }
    for (size_t i = 0; i < out.len; ++i) out.data[i] = b[i];
  }
  *f = out;
  return true;
}

// ---------------------------------------------------------------- acceptance filters
// A hardware filter passes a frame when (ID word & AFMR) == (AFIR & AFMR). A HAL filter of a
// given identifier width maps onto one; IdType::kAny does not in the chip's layout (a standard
// and an extended identifier sit at different bits), so the driver filters those in software.
constexpr bool encode_filter(const CanFilter& f, FrameWordLayout layout, uint32_t* mask,
                             uint32_t* id) {
  if (layout == FrameWordLayout::kQemu72) {
    // can_id layout: the width flag is bit 31; kAny leaves it out of the mask.
    const uint32_t width = f.type == IdType::kExtended ? kExtIdMask : kStdIdMask;
    const uint32_t m = f.mask & (f.type == IdType::kAny ? kExtIdMask : width);
    *mask = m | (f.type == IdType::kAny ? 0u : kQemuEff);
    *id = (f.id & m) | (f.type == IdType::kExtended ? kQemuEff : 0u);
    return true;
  }
  if (f.type == IdType::kStandard) {
    *mask = (f.mask & 0x7FFu) << 21 | 1u << 19;  // IDE must be 0
    *id = (f.id & f.mask & 0x7FFu) << 21;
    return true;
  }
  if (f.type == IdType::kExtended) {
    const uint32_t m = f.mask & kExtIdMask;
    const uint32_t i = f.id & m;
    *mask = ((m >> 18) & 0x7FFu) << 21 | 1u << 19 | (m & 0x3FFFFu) << 1;
    *id = ((i >> 18) & 0x7FFu) << 21 | 1u << 19 | (i & 0x3FFFFu) << 1;
    return true;
  }
  return false;
}

// ---------------------------------------------------------------- error state
// SR as the HAL's states: configuration mode (SR.CONFIG) is kDown, off the bus; then ESTAT:
// 01 error-active (error-warning when ERRWRN: a counter reached 96), 11 error-passive,
// 10 bus-off. ESTAT 00 outside configuration mode does not occur on the chip; QEMU 7.2's
// model never updates ESTAT (it has no error counters), so a running modelled controller reads
// 00 and is error-active.
constexpr BusState bus_state_from(uint32_t sr) {
  if ((sr & can_reg::kSrConfig) != 0) return BusState::kDown;
  switch ((sr >> can_reg::kSrEstatShift) & 3u) {
    case 3:
      return BusState::kErrorPassive;
    case 2:
      return BusState::kBusOff;
    default:
      return (sr & can_reg::kSrErrWrn) != 0 ? BusState::kErrorWarning : BusState::kErrorActive;
  }
}

}  // namespace curio::hal::zynqmp
