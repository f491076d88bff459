// The ZynqMP's UART (Cadence UART; UART0 at 0xFF000000, UG1087 "UART") as a polled
// hal::SerialPort: the board's log. Registers: CR 0x00 (RXRES 0, TXRES 1, RXEN 2, TXEN 4),
// MR 0x04 (0x20: 8 bits, no parity, 1 stop), SR 0x2C (RXEMPTY 1, TXFULL 4), FIFO 0x30
// (64 bytes each way). QEMU does not pace the line by the baud generator, so init() leaves it
// at its reset value; a board sets BAUDGEN/BAUDDIV for its reference clock. Firmware-clean.
#pragma once
#include <cstdint>

#include "hal/serial_port.hpp"

namespace curio::hal::zynqmp {

inline constexpr uintptr_t kUart0Base = 0xFF000000u;

class CadenceUart final : public SerialPort {
 public:
  explicit CadenceUart(uintptr_t base = kUart0Base) : base_(base) {}

  void init();
  bool try_write(uint8_t byte) override;
  bool try_read(uint8_t* byte) override;
  // Blocking text output (the log).
  void write(const char* text);

 private:
  volatile uint32_t* reg(uint32_t offset) const {
    return reinterpret_cast<volatile uint32_t*>(base_ + offset);
  }
  uintptr_t base_;
};

}  // namespace curio::hal::zynqmp
