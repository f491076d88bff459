// firmware.zynqmp.can_controller: the controller image for QEMU's xlnx-zcu102 whose CAN link
// is the ZynqMP's own CAN controller (CAN0, hal/zynqmp/zynqmp_can.hpp: interrupt-driven,
// register level), joined to Linux SocketCAN by QEMU's can-host-socketcan: the real Controller
// (firmware/app) with the full-size Explorer, against `curio-sim serve` on the same interface
// (tests/uml/zynqmp_can_uml.sh runs both inside User-mode Linux). The log goes to UART0 (the
// board's console); the last lines carry the archive's FNV-1a checksum, which must equal
// `curio-controller --print-checksum` for the same algorithm and seed, and the link's rates.
//
// Run parameters (the semihosting command line; run-zcu102.sh IMAGE ARG...):
//   algo=MGE-EFR|RGE-EFR|RPE|MGE-bVAE   seed=N   episodes=N (after the bootstrap)
//   bootstrap=N (default: 100 EFR, 400 βVAE)   progress=N (a line every N episodes, 0 = none)
//   layout=qemu|chip (default qemu): the frame words QEMU 7.2's model passes to Linux intact
//   (qemu), or the chip's (UG1087), which reach Linux garbled through QEMU's bridge
// The bus is classic CAN 2.0B, so the arm protocol runs its classic profile. Every other
// setting is curio-controller's (σ 0.05, D 1 EFR / 2 learned, window 1000, ε 0.1).
#include <cstdint>
#include <cstring>

#include "firmware/app/controller.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/nn/encoder.hpp"
#include "firmware/nn/models/beta_vae_weights.hpp"
#include "hal/zynqmp/cadence_uart.hpp"
#include "hal/zynqmp/generic_timer.hpp"
#include "hal/zynqmp/gic.hpp"
#include "hal/zynqmp/zynqmp_can.hpp"
#include "tests/app/qemu_app/image_run_args.hpp"
#include "tests/app/qemu_app/image_run_report.hpp"
#include "toolchain/qemu/semihosting.h"

namespace {

using namespace curio;

// The run parameters and curio-controller's configuration for them, shared with the SLCAN
// image (tests/app/qemu_app/image_run_args.hpp), with layout= as the link option.
using RunArgs = test::ImageRunArgs;
constexpr test::ImageLinkOption kLinkOption{"layout", "qemu", "chip"};

hal::zynqmp::CadenceUart g_uart;
void print(const char* s) {
  g_uart.write(s);
}
void print_u32(uint64_t v) {
  char buf[21];
  int i = 20;
  buf[i] = '\0';
  do {
    buf[--i] = static_cast<char>('0' + v % 10u);
    v /= 10u;
  } while (v != 0u);
  print(&buf[i]);
}
void print_hex32(uint32_t v) {
  static const char kDigits[] = "0123456789abcdef";
  char buf[11] = {'0', 'x'};
  for (int i = 0; i < 8; ++i) buf[2 + i] = kDigits[(v >> (28 - 4 * i)) & 0xFu];
  buf[10] = '\0';
  print(buf);
}
constexpr test::ImagePrinter kPrinter{print, print_u32, print_hex32};

// Static storage: the full-size Explorer, the controller, the encoder and the bus.
Explorer g_explorer;
app::Controller g_controller;
nn::Encoder g_encoder(nn::beta_vae::kEncoderModel);
hal::zynqmp::GenericTimer g_timer;
void idle(void* timer, uint64_t until_us) {
  static_cast<hal::zynqmp::GenericTimer*>(timer)->idle_until(until_us);
}
hal::zynqmp::ZynqmpCan g_can(&g_timer, &idle, &g_timer);
char g_cmdline[256];

}  // namespace

int main() {
  g_uart.init();
  RunArgs args;
  if (curio_semihost_cmdline(g_cmdline, sizeof g_cmdline) >= 0 && !test::parse_image_args(g_cmdline, kLinkOption, &args)) {
    print(
        "can controller: bad command line (algo= seed= episodes= bootstrap= progress= "
        "layout=qemu|chip)\n");
    return 2;
  }
  ExplorerConfig config;
  bool learned = false;
  if (!test::image_explorer_config(args, &config, &learned)) {
    print("can controller: unknown algorithm or invalid configuration\n");
    return 2;
  }
  hal::zynqmp::Gic::init();
  g_timer.init();
  hal::zynqmp::irq_enable();
  hal::zynqmp::ZynqmpCanConfig cc_bus;
  cc_bus.layout = args.link_alt ? hal::zynqmp::FrameWordLayout::kUg1085
                                   : hal::zynqmp::FrameWordLayout::kQemu72;
  if (g_can.init(cc_bus) != hal::zynqmp::ZynqmpCanInit::kOk) {
    print("can controller: CAN0 init failed\n");
    return 1;
  }
  if (g_explorer.init(config) != Status::kOk) {
    print("can controller: explorer init failed\n");
    return 1;
  }
  // curio-controller's defaults, with the timeouts widened for QEMU inside User-mode Linux
  // (emulated code there runs ~8x slower than on the host, and the serve shares UML's one
  // CPU). Timeouts only decide when a fault is declared; without faults the exploration, and
  // so the archive, is the same.
  // A classic-profile camera image is 1,757 frames, which QEMU inside UML delivers at
  // ≈ 400–1,000 frames/s: the heartbeats queued behind it arrive seconds late, and the
  // transfer itself takes seconds.
  app::ControllerConfig cc;
  cc.heartbeat_timeout_us = 10'000'000;
  cc.sdo_timeout_us = 5'000'000;
  cc.boot_timeout_us = 5'000'000;
  cc.feedback_timeout_us = 5'000'000;
  cc.capture_timeout_us = 30'000'000;
  cc.recovery_timeout_us = 10'000'000;
  cc.tx_deadline_us = 1'000'000;
  app::AppStatus s = g_controller.init(&g_can, &g_explorer, cc, learned ? &g_encoder : nullptr);
  if (s == app::AppStatus::kOk) s = g_controller.start_arm();
  print("can controller on the ZynqMP (QEMU xlnx-zcu102, Cortex-A53 AArch32), CAN0 at ");
  print_u32(cc_bus.bitrate / 1000);
  print(" kbit/s (BRP ");
  print_u32(g_can.bit_timing().brp);
  print(", ");
  print_u32(g_can.bit_timing().tq_per_bit());
  print(" tq, sample point ");
  print_u32(g_can.bit_timing().sample_point_permille);
  print(" permille), frame words ");
  print(args.link_alt ? "UG1087" : "QEMU 7.2");
  print(": ");
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
  print(protocol::to_string(protocol::profile_for(g_can.carries_fd())));
  print("\n  start_arm: ");
  print(app::to_string(s));
  print("\n");
  if (s != app::AppStatus::kOk) {
    // The faults that stopped the bring-up, by the names the Linux controller reports.
    const app::ControllerCounters& c = g_controller.counters();
    print("  faults ");
    print_u32(c.fault_total);
    print(" (last ");
    print(app::to_string(c.last_fault));
    print("), duplicate answers ");
    print_u32(c.duplicate_answers);
    print(", other-master frames ");
    print_u32(c.other_master_frames);
    test::print_fault_kinds(kPrinter, c);
    print("\nFAILED\n");
    return 1;
  }
  const uint8_t physics = g_controller.query_physics();
  print("  arm physics: ");
  print(physics == 1 ? "ODE" : physics == 0 ? "kinematic" : "unknown");
  print("\n");

  const uint64_t t0 = g_timer.now_us();
  int episodes = 0;
  while (!g_explorer.done()) {
    s = g_controller.run_episode();
    if (s != app::AppStatus::kOk) break;
    ++episodes;
    if (args.progress > 0 && episodes % args.progress == 0) {
      print("  episode ");
      print_u32(static_cast<uint32_t>(episodes));
      print(", ");
      print_u32((g_timer.now_us() - t0) / 1000);
      print(" ms\n");
    }
  }
  const uint64_t us = g_timer.now_us() - t0;
  g_controller.stop_arm();

  const app::ControllerCounters& c = g_controller.counters();
  const hal::CanStats bs = g_can.stats();
  const hal::zynqmp::ZynqmpCanCounters& dc = g_can.counters();
  print("  last episode ");
  print(app::to_string(s));
  print(", episodes ");
  print_u32(static_cast<uint32_t>(episodes));
  print(" in ");
  print_u32(us / 1000);
  print(" ms (image clock): ");
  print_u32(episodes > 0 ? us / 1000 / static_cast<uint64_t>(episodes) : 0);
  print(" ms per episode, ");
  print_u32(us > 0 ? (c.frames_sent + c.frames_received) * 1'000'000 / us : 0);
  print(" frames/s\n  frames sent ");
  print_u32(c.frames_sent);
  print(", received ");
  print_u32(c.frames_received);
  print("; driver: interrupts ");
  print_u32(dc.interrupts);
  print(", TX windows ");
  print_u32(dc.tx_windows);
  print(", rx_dropped ");
  print_u32(bs.rx_dropped);
  print(" (hardware FIFO overflows ");
  print_u32(dc.rx_hw_overflows);
  print(")");
  print(", tx_timedout ");
  print_u32(bs.tx_timedout);
  print(", tx_rejected ");
  print_u32(bs.tx_rejected);
  print(", undecodable ");
  print_u32(dc.rx_undecodable);
  print(", state ");
  print(hal::to_string(g_can.state()));
  print(", TEC/REC ");
  print_u32(g_can.tx_error_counter());
  print("/");
  print_u32(g_can.rx_error_counter());
  print("\n  node reboots ");
  print_u32(c.node_reboots);
  print(", other-master frames ");
  print_u32(c.other_master_frames);
  print(", duplicate answers ");
  print_u32(c.duplicate_answers);
  print("; faults ");
  return test::print_run_end(kPrinter, c, learned ? &g_encoder : nullptr, g_explorer,
                             s == app::AppStatus::kOk && g_explorer.done());
}
