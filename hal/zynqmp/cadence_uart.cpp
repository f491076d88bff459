// Cadence UART, polled (cadence_uart.hpp).
#include "hal/zynqmp/cadence_uart.hpp"

namespace curio::hal::zynqmp {
namespace {
constexpr uint32_t kCr = 0x00;
constexpr uint32_t kMr = 0x04;
constexpr uint32_t kSr = 0x2C;
constexpr uint32_t kFifo = 0x30;
constexpr uint32_t kCrRxRes = 1u << 0;
constexpr uint32_t kCrTxRes = 1u << 1;
constexpr uint32_t kCrRxEn = 1u << 2;
constexpr uint32_t kCrTxEn = 1u << 4;
constexpr uint32_t kSrRxEmpty = 1u << 1;
constexpr uint32_t kSrTxFull = 1u << 4;
}  // namespace

void CadenceUart::init() {
  *reg(kCr) = kCrRxRes | kCrTxRes;
  *reg(kMr) = 0x20u;
  *reg(kCr) = kCrRxEn | kCrTxEn;
}

bool CadenceUart::try_write(uint8_t byte) {
  if ((*reg(kSr) & kSrTxFull) != 0) return false;
  *reg(kFifo) = byte;
  return true;
}

bool CadenceUart::try_read(uint8_t* byte) {
  if ((*reg(kSr) & kSrRxEmpty) != 0) return false;
  *byte = static_cast<uint8_t>(*reg(kFifo));
  return true;
}

void CadenceUart::write(const char* text) {
  for (; *text != '\0'; ++text) {
    while (!try_write(static_cast<uint8_t>(*text))) {
    }
  }
}

}  // namespace curio::hal::zynqmp
