// firmware.app.slcan_echo: the link alone, for its rates (docs/can.md, "SLCAN"): the image
// echoes every frame it receives over SLCAN on UART0 (hal::SlcanBus, as the controller image
// uses it) with id + 1, until `frames=N` came in, then prints the counts and its own timing.
// Command line (semihosting): frames=N (default 1000), echo=0 (receive only: the RX rate).
#include <cstdint>
#include <cstring>

#include "hal/mps2/cmsdk_timer_clock.hpp"
#include "hal/mps2/cmsdk_uart.hpp"
#include "hal/slcan/slcan_bus.hpp"
#include "toolchain/qemu/semihosting.h"

namespace {

using namespace curio;

hal::mps2::CmsdkUart g_uart;
hal::mps2::CmsdkTimerClock g_clock;
hal::SlcanBus g_bus(&g_uart, &g_clock, protocol::SlcanMode::kFd);
char g_cmdline[128];

uint32_t arg(const char* line, const char* key, uint32_t fallback) {
  const char* p = std::strstr(line, key);
  if (p == nullptr) return fallback;
  p += std::strlen(key);
  uint32_t v = 0;
  while (*p >= '0' && *p <= '9') v = v * 10u + static_cast<uint32_t>(*p++ - '0');
  return v;
}

}  // namespace

int main() {
  if (curio_semihost_cmdline(g_cmdline, sizeof g_cmdline) < 0) g_cmdline[0] = '\0';
  const uint32_t frames = arg(g_cmdline, "frames=", 1000);
  const uint32_t echo = arg(g_cmdline, "echo=", 1);
  g_uart.init();
  g_clock.init();
  uint32_t got = 0;
  uint64_t t_first = 0;
  hal::CanFrame batch[16];
  while (got < frames) {
    size_t n = 0;
    if (g_bus.receive_wait(batch, 16, &n, 10'000'000) != hal::CanStatus::kOk) break;
    if (got == 0) t_first = g_clock.now_us();
    for (size_t i = 0; i < n; ++i) batch[i].id = (batch[i].id + 1) & hal::kStdIdMask;
    if (echo != 0) g_bus.send_batch(batch, n, g_clock.now_us() + 1'000'000, nullptr);
    got += static_cast<uint32_t>(n);
  }
  const uint64_t us = g_clock.now_us() - t_first;
  curio_semihost_print("slcan echo: ");
  curio_semihost_print_u32(got);
  curio_semihost_print(" frames echoed in ");
  curio_semihost_print_u32(static_cast<uint32_t>(us / 1000));
  curio_semihost_print(" ms (image clock), bytes in ");
  curio_semihost_print_u32(static_cast<uint32_t>(g_bus.rx_bytes()));
  curio_semihost_print(", out ");
  curio_semihost_print_u32(static_cast<uint32_t>(g_bus.tx_bytes()));
  curio_semihost_print(", malformed lines ");
  curio_semihost_print_u32(static_cast<uint32_t>(g_bus.stats().errors));
  curio_semihost_print("\n");
  return got == frames ? 0 : 1;
}
