// The wire protocol between the host's bus contract test (tests/hal/zynqmp_can_test.cpp) and
// the contract server image (contract_server_main.cpp) on QEMU's xlnx-zcu102: each hal::CanBus
// call on a host-side endpoint becomes one request on UART0 and runs on the image's driver,
// endpoint 0 = CAN0, 1 = CAN1 (both on one QEMU CAN bus). Little-endian on both sides; frames,
// filters and statistics travel as the structs' bytes (their layouts are the same for x86-64
// and AArch32, checked below). Firmware-clean.
#pragma once
#include <cstdint>

#include "hal/can_bus.hpp"

namespace curio::zynqmp_rpc {

inline constexpr uint8_t kRequestMagic = 0xC5;
inline constexpr uint8_t kReplyMagic = 0x5C;
// Sent once by the image when its UART receives: bytes that reach QEMU's UART before the
// guest enables its receiver are lost, so the host sends nothing before this byte.
inline constexpr uint8_t kReadyMagic = 0xA5;
inline constexpr uint32_t kMaxFrames = 64;  // per send or receive request
inline constexpr uint32_t kMaxPayload = 8 + 4 + kMaxFrames * sizeof(hal::CanFrame);

enum class Op : uint8_t {
  kReset = 1,  // payload: layout u8 (FrameWordLayout); both controllers reinitialised
  kSend,       // deadline u64, count u32, frames → accepted u32
  kReceive,    // capacity u32 → count u32, frames
  kWait,       // timeout_us u64
  kFilters,    // count u32, filters
  kStats,      // → CanStats
  kState,      // → BusState u8
  kNow,        // → u64
  kCarriesFd,  // → u8
  kExit,       // the image exits 0
};

struct RequestHeader {
  uint8_t magic = kRequestMagic;
  Op op = Op::kNow;
  uint8_t endpoint = 0;
  uint8_t reserved = 0;
  uint32_t length = 0;  // payload bytes that follow
};

struct ReplyHeader {
  uint8_t magic = kReplyMagic;
  uint8_t status = 0;  // hal::CanStatus
  uint16_t reserved = 0;
  uint32_t length = 0;
};

static_assert(sizeof(RequestHeader) == 8 && sizeof(ReplyHeader) == 8, "wire headers");
static_assert(sizeof(hal::CanFrame) == 72, "frame layout on the wire");
static_assert(sizeof(hal::CanFilter) == 12, "filter layout on the wire");
static_assert(sizeof(hal::CanStats) == 64, "statistics layout on the wire");

}  // namespace curio::zynqmp_rpc
