// CMSDK APB UART, polled (cmsdk_uart.hpp).
#include "hal/mps2/cmsdk_uart.hpp"

namespace curio::hal::mps2 {

namespace {
constexpr uint32_t kData = 0x00;
constexpr uint32_t kState = 0x04;
constexpr uint32_t kCtrl = 0x08;
constexpr uint32_t kBaudDiv = 0x10;
constexpr uint32_t kStateTxFull = 1u << 0;
constexpr uint32_t kStateRxFull = 1u << 1;
constexpr uint32_t kCtrlTxRx = 0x3u;
}  // namespace

void CmsdkUart::init(uint32_t bauddiv) {
  *reg(kBaudDiv) = bauddiv < 16 ? 16 : bauddiv;
  *reg(kCtrl) = kCtrlTxRx;
}

bool CmsdkUart::try_write(uint8_t byte) {
  if ((*reg(kState) & kStateTxFull) != 0) return false;
  *reg(kData) = byte;
  return true;
}

bool CmsdkUart::try_read(uint8_t* byte) {
  if ((*reg(kState) & kStateRxFull) == 0) return false;
  *byte = static_cast<uint8_t>(*reg(kData) & 0xFFu);
  return true;
}

}  // namespace curio::hal::mps2
