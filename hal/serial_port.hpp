// A byte-stream serial port (a UART, a host pty or socket) as the HAL sees it: non-blocking
// byte in, byte out. Backends: hal/mps2/cmsdk_uart (QEMU's mps2 UART); an MCU port supplies
// its own UART driver behind this. Firmware-clean: no heap, no OS headers.
#pragma once
#include <cstdint>

namespace curio::hal {

class SerialPort {
 public:
  virtual ~SerialPort() = default;
  // Hands one byte to the transmitter; false (byte not taken) while it is full.
  virtual bool try_write(uint8_t byte) = 0;
  // Takes one received byte; false when none is waiting.
  virtual bool try_read(uint8_t* byte) = 0;
};

}  // namespace curio::hal
