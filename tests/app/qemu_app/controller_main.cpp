// firmware.app.qemu_controller (Cortex-M7, QEMU mps2-an500) and firmware.app.host_controller
// (the same program built for the host): the real controller (firmware/app) explores the
// in-image fake arm over the in-image bus (controller_run.hpp), prints the run's checksums,
// exploration ratio and counters, and fails unless the run is clean and the checksums equal
// the host's golden values. The host build also replays the exploration in-process against
// sim::KinematicWorld (CURIO_QAPP_SIM_ORACLE): the fake arm must produce the same archive.
#include <cstdint>

#include "tests/app/qemu_app/controller_run.hpp"

#if defined(CURIO_QAPP_QEMU)
#include "toolchain/qemu/semihosting.h"
static void print(const char* s) { curio_semihost_print(s); }
static void print_u32(uint32_t v) { curio_semihost_print_u32(v); }
static void print_hex32(uint32_t v) { curio_semihost_print_hex32(v); }
#else
#include <cstdio>
static void print(const char* s) { std::fputs(s, stdout); }
static void print_u32(uint32_t v) { std::printf("%u", static_cast<unsigned>(v)); }
static void print_hex32(uint32_t v) { std::printf("0x%08x", static_cast<unsigned>(v)); }
#endif

#if defined(CURIO_QAPP_SIM_ORACLE)
uint32_t sim_oracle_archive_checksum();  // sim_oracle.cpp (host only)
#endif

namespace {
curio::test::ControllerScenario g_scenario;  // static storage: .bss
}

int main() {
  using namespace curio::test;
  const ScenarioResult r = g_scenario.run();
  const curio::app::ControllerCounters& c = r.counters;
  print("controller on ");
#if defined(CURIO_QAPP_QEMU)
  print("Cortex-M7 (QEMU mps2-an500)");
#else
  print("host");
#endif
  print(": MGE-EFR seed ");
  print_u32(static_cast<uint32_t>(kScenarioSeed));
  print(", archive capacity ");
  print_u32(static_cast<uint32_t>(curio::kArchiveCapacity));
  print("\n  start ");
  print(curio::app::to_string(r.start));
  print(", last episode ");
  print(curio::app::to_string(r.last));
  print(", episodes ");
  print_u32(static_cast<uint32_t>(r.episodes));
  print(", grasps ");
  print_u32(static_cast<uint32_t>(r.grasps));
  print(", exploration ratio ");
  print_u32(static_cast<uint32_t>(r.visited_cells));
  print("/900\n  frames sent ");
  print_u32(static_cast<uint32_t>(c.frames_sent));
  print(", received ");
  print_u32(static_cast<uint32_t>(c.frames_received));
  print(", sync cycles ");
  print_u32(static_cast<uint32_t>(c.sync_cycles));
  print(", faults ");
  print_u32(static_cast<uint32_t>(c.fault_total));
  print(" (last ");
  print(curio::app::to_string(c.last_fault));
  print("), replays ");
  print_u32(static_cast<uint32_t>(c.replays));
  print(", unexpected/malformed/foreign ");
  print_u32(static_cast<uint32_t>(c.unexpected_frames));
  print("/");
  print_u32(static_cast<uint32_t>(c.malformed_frames));
  print("/");
  print_u32(static_cast<uint32_t>(c.foreign_frames));
  print("\n  arm: world steps ");
  print_u32(r.arm.steps);
  print(", heartbeats ");
  print_u32(r.arm.heartbeats);
  print(", sdo ");
  print_u32(r.arm.sdo_requests);
  print(", captures ");
  print_u32(r.arm.captures);
  print(", virtual bus time ");
  print_u32(static_cast<uint32_t>(r.virtual_us / 1000));
  print(" ms\n  archive checksum ");
  print_hex32(r.archive_checksum);
  print(" (host golden ");
  print_hex32(kControllerArchiveChecksum);
  print("), wire checksum ");
  print_hex32(r.wire_checksum);
  print(" (host golden ");
  print_hex32(kControllerWireChecksum);
  print(")\n  hand checksum ");
  print_hex32(r.hand_checksum);
  print(" (host golden ");
  print_hex32(kControllerHandChecksum);
  print(")\n");

  int failures = scenario_failures(r, g_scenario);
  if (failures != 0) print("FAIL: the run was not clean (status, episode count, faults or frames)\n");
  if (r.archive_checksum != kControllerArchiveChecksum) {
    print("FAIL: archive checksum differs from the host's golden value\n");
    ++failures;
  }
  if (r.wire_checksum != kControllerWireChecksum) {
    print("FAIL: wire checksum differs from the host's golden value\n");
    ++failures;
  }
  if (r.hand_checksum != kControllerHandChecksum) {
    print("FAIL: final hand positions (float32 of cos/sin sums) differ from the host's\n");
    ++failures;
  }
#if defined(CURIO_QAPP_SIM_ORACLE)
  const uint32_t oracle = sim_oracle_archive_checksum();
  print("  sim::KinematicWorld in-process archive checksum ");
  print_hex32(oracle);
  print("\n");
  if (oracle != r.archive_checksum) {
    print("FAIL: the fake arm's archive differs from sim::KinematicWorld's in-process archive\n");
    ++failures;
  }
#endif
  print(failures == 0 ? "PASS\n" : "FAILED\n");
  return failures == 0 ? 0 : 1;
}
