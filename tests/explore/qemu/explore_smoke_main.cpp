// Cortex-M7 (QEMU mps2-an500) run of the explore smoke scenario: the core runs heap-free from
// static storage, the run is repeatable, and its checksum equals the host's golden value.
#include "tests/explore/explore_smoke.hpp"
#include "toolchain/qemu/semihosting.h"

namespace {
curio::Explorer g_explorer;  // static storage: .bss
}

int main() {
  using curio::test::run_smoke;
  const curio::test::SmokeResult first = run_smoke(g_explorer);
  const curio::test::SmokeResult again = run_smoke(g_explorer);
  curio_semihost_print("explore smoke: capacity ");
  curio_semihost_print_u32(static_cast<uint32_t>(curio::kArchiveCapacity));
  curio_semihost_print(", episodes ");
  curio_semihost_print_u32(static_cast<uint32_t>(first.episodes));
  curio_semihost_print(", nn queries ");
  curio_semihost_print_u32(first.nn_queries);
  curio_semihost_print(", checksum ");
  curio_semihost_print_hex32(first.checksum);
  curio_semihost_print(" (host golden ");
  curio_semihost_print_hex32(curio::test::kSmokeChecksum);
  curio_semihost_print(")\n");
  int failures = 0;
  if (first.status != curio::Status::kOk) {
    curio_semihost_print("FAIL: status ");
    curio_semihost_print(curio::to_string(first.status));
    curio_semihost_print("\n");
    ++failures;
  }
  if (first.episodes != curio::test::kSmokeBootstrap + curio::test::kSmokeEpisodes) {
    curio_semihost_print("FAIL: wrong episode count\n");
    ++failures;
  }
  if (again.checksum != first.checksum) {
    curio_semihost_print("FAIL: second run differs\n");
    ++failures;
  }
  if (first.checksum != curio::test::kSmokeChecksum) {
    curio_semihost_print("FAIL: checksum differs from the host's\n");
    ++failures;
  }
  curio_semihost_print(failures == 0 ? "PASS\n" : "FAILED\n");
  return failures == 0 ? 0 : 1;
}
