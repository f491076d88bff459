// firmware.app.slcan_controller: the controller image for QEMU's mps2-an500 (Cortex-M7) whose
// CAN link is real: hal::SlcanBus over UART0 (CMSDK APB UART, polled), timed by the CMSDK
// timer, running the real Controller (firmware/app) with the full-size Explorer against the
// arm on the far side of the link (`curio-can slcan-bridge` → `curio-sim serve`). It prints
// the archive's FNV-1a checksum, which must equal `curio-controller --print-checksum` on the
// host for the same algorithm and seed (tests/app/qemu_slcan/qemu_slcan_e2e.sh).
//
// Run parameters come from the semihosting command line
// (-semihosting-config enable=on,target=native,arg=algo=MGE-EFR,arg=seed=0,arg=episodes=400):
//   algo=MGE-EFR|RGE-EFR|RPE|MGE-bVAE   seed=N   episodes=N (after the bootstrap)
//   bootstrap=N (default: 100 EFR, 400 βVAE)   progress=N (a line every N episodes, 0 = none)
//   can=fd|classic (default fd): the link's SLCAN mode and so the protocol's profile. classic
//   sends t/T lines only, as the kernel's slcan and Lawicel adapters take them.
// The defaults of everything else are curio-controller's (σ 0.05, D 1 EFR / 2 learned,
// window 1000, ε 0.1), so the two runs are the same exploration.
#include <cstdint>
#include <cstring>

#include "firmware/app/controller.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/nn/encoder.hpp"
#include "firmware/nn/models/beta_vae_weights.hpp"
#include "hal/mps2/cmsdk_timer_clock.hpp"
#include "hal/mps2/cmsdk_uart.hpp"
#include "hal/slcan/slcan_bus.hpp"
#include "tests/app/qemu_app/image_run_args.hpp"
#include "tests/app/qemu_app/image_run_report.hpp"
#include "toolchain/qemu/semihosting.h"

namespace {

using namespace curio;

using RunArgs = test::ImageRunArgs;
constexpr test::ImageLinkOption kLinkOption{"can", "fd", "classic"};

void print(const char* s) {
  curio_semihost_print(s);
}
void print_u32(uint64_t v) {
  curio_semihost_print_u32(static_cast<uint32_t>(v));
}
constexpr test::ImagePrinter kPrinter{print, print_u32, curio_semihost_print_hex32};

// Static storage: the full-size Explorer (~3 MB), the controller, the encoder and the link.
Explorer g_explorer;
app::Controller g_controller;
nn::Encoder g_encoder(nn::beta_vae::kEncoderModel);
hal::mps2::CmsdkUart g_uart;
hal::mps2::CmsdkTimerClock g_clock;
// One link per mode (the command line picks one before any byte moves).
hal::SlcanBus g_bus_fd(&g_uart, &g_clock, protocol::SlcanMode::kFd);
hal::SlcanBus g_bus_classic(&g_uart, &g_clock, protocol::SlcanMode::kClassic);
char g_cmdline[256];

}  // namespace

int main() {
  RunArgs args;
  if (curio_semihost_cmdline(g_cmdline, sizeof g_cmdline) >= 0 && !test::parse_image_args(g_cmdline, kLinkOption, &args)) {
    print(
        "slcan controller: bad command line (algo= seed= episodes= bootstrap= progress= "
        "can=fd|classic)\n");
    return 2;
  }
  ExplorerConfig config;
  bool learned = false;
  if (!test::image_explorer_config(args, &config, &learned)) {
    print("slcan controller: unknown algorithm or invalid configuration\n");
    return 2;
  }
  g_uart.init();
  g_clock.init();
  if (g_explorer.init(config) != Status::kOk) {
    print("slcan controller: explorer init failed\n");
    return 1;
  }
  // curio-controller's defaults, but with the timeouts of a slow serial link rather than of
  // a 1 Mbit/s bus: QEMU hands the UART one received byte per main-loop turn (≈ 10–20 kB/s
  // measured on a loaded 2-core host, docs/can.md), so a reply can queue behind a few
  // hundred milliseconds of earlier lines. Timeouts only decide when a fault is declared;
  // without faults the exploration, and so the archive, is the same. Heartbeats every
  // 500 ms instead of 100 ms leave more of the link to the control traffic.
  app::ControllerConfig cc;
  cc.heartbeat_producer_ms = 500;
  cc.heartbeat_timeout_us = 5'000'000;
  cc.sdo_timeout_us = 2'000'000;
  cc.boot_timeout_us = 5'000'000;
  cc.feedback_timeout_us = 2'000'000;
  cc.capture_timeout_us = 5'000'000;
  cc.recovery_timeout_us = 10'000'000;
  cc.tx_deadline_us = 2'000'000;
  hal::SlcanBus& bus = args.link_alt ? g_bus_classic : g_bus_fd;
  app::AppStatus s = g_controller.init(&bus, &g_explorer, cc, learned ? &g_encoder : nullptr);
  if (s == app::AppStatus::kOk) s = g_controller.start_arm();
  print("slcan controller on Cortex-M7 (QEMU mps2-an500), SLCAN over UART0: ");
  print(args.algo);
  print(" seed ");
  print_u32(args.seed);
  print(", ");
  print_u32(static_cast<uint32_t>(config.n_bootstrap));
  print(" + ");
  print_u32(static_cast<uint32_t>(config.n_episodes));
  print(" episodes, archive capacity ");
  print_u32(static_cast<uint32_t>(kArchiveCapacity));
  print(", CAN profile ");
  print(protocol::to_string(protocol::profile_for(bus.carries_fd())));
  print("\n  start_arm: ");
  print(app::to_string(s));
  print("\n");
  if (s != app::AppStatus::kOk) return 1;
  const uint8_t physics = g_controller.query_physics();
  print("  arm physics: ");
  print(physics == 1 ? "ODE" : physics == 0 ? "kinematic" : "unknown");
  print("\n");

  const uint64_t t0 = g_clock.now_us();
  int episodes = 0;
  while (!g_explorer.done()) {
    s = g_controller.run_episode();
    if (s != app::AppStatus::kOk) break;
    ++episodes;
    if (args.progress > 0 && episodes % args.progress == 0) {
      print("  episode ");
      print_u32(static_cast<uint32_t>(episodes));
      print(", ");
      print_u32((g_clock.now_us() - t0) / 1000);
      print(" ms\n");
    }
  }
  const uint64_t ms = (g_clock.now_us() - t0) / 1000;
  g_controller.stop_arm();

  const app::ControllerCounters& c = g_controller.counters();
  const hal::CanStats bs = bus.stats();
  print("  last episode ");
  print(app::to_string(s));
  print(", episodes ");
  print_u32(static_cast<uint32_t>(episodes));
  print(" in ");
  print_u32(ms);
  print(" ms (image clock)\n  frames sent ");
  print_u32(c.frames_sent);
  print(", received ");
  print_u32(c.frames_received);
  print("; serial bytes out ");
  print_u32(bus.tx_bytes());
  print(", in ");
  print_u32(bus.rx_bytes());
  print("; malformed lines ");
  print_u32(bs.errors);
  print("\n  faults ");
  return test::print_run_end(kPrinter, c, learned ? &g_encoder : nullptr, g_explorer,
                             s == app::AppStatus::kOk && g_explorer.done());
}
