// Checks and output for the ZynqMP test images: the log goes to UART0 (the board's console,
// QEMU's stdout under run-zcu102.sh) and failures are counted; main() returns the count.
#pragma once
#include <cstdint>

#include "hal/zynqmp/cadence_uart.hpp"

namespace curio::zynqmp_test {

inline hal::zynqmp::CadenceUart g_console;
inline uint32_t g_failures = 0;

inline void print(const char* s) {
  g_console.write(s);
}
inline void print_u32(uint64_t v) {
  char buf[21];
  int i = 20;
  buf[i] = '\0';
  do {
    buf[--i] = static_cast<char>('0' + v % 10u);
    v /= 10u;
  } while (v != 0u);
  print(&buf[i]);
}
inline void print_hex32(uint32_t v) {
  static const char kDigits[] = "0123456789abcdef";
  char buf[11] = {'0', 'x'};
  for (int i = 0; i < 8; ++i) buf[2 + i] = kDigits[(v >> (28 - 4 * i)) & 0xFu];
  buf[10] = '\0';
  print(buf);
}

inline void check(bool ok, const char* what, int line) {
  if (ok) return;
  ++g_failures;
  print("FAILED (line ");
  print_u32(static_cast<uint32_t>(line));
  print("): ");
  print(what);
  print("\n");
}

}  // namespace curio::zynqmp_test

#define ZCHECK(cond) ::curio::zynqmp_test::check((cond), #cond, __LINE__)
