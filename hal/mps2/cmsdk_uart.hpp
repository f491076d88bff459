// The ARM CMSDK APB UART of the MPS2 boards (QEMU -M mps2-an500: UART0 at 0x40004000) as a polled
// hal::SerialPort. Registers (ARM's CMSDK reference, as QEMU models them): DATA 0x00,
// STATE 0x04 (bit 0 TX full, bit 1 RX full), CTRL 0x08 (bit 0 TX enable, bit 1 RX enable),
// BAUDDIV 0x10 (≥ 16).
// No interrupts: the one-byte RX holding register is read when the bus polls; under QEMU the
// chardev backend holds further bytes until it is empty, so nothing is lost.
#pragma once
#include <cstdint>

#include "hal/serial_port.hpp"

namespace curio::hal::mps2 {

inline constexpr uintptr_t kUart0Base = 0x40004000u;

class CmsdkUart final : public SerialPort {
 public:
  explicit CmsdkUart(uintptr_t base = kUart0Base) : base_(base) {}

  // Enables TX and RX with baud divisor `bauddiv` (QEMU does not pace the line by it).
  void init(uint32_t bauddiv = 16);

  bool try_write(uint8_t byte) override;
  bool try_read(uint8_t* byte) override;

 private:
  volatile uint32_t* reg(uint32_t offset) const {
    return reinterpret_cast<volatile uint32_t*>(base_ + offset);
  }
  uintptr_t base_;
};

}  // namespace curio::hal::mps2
