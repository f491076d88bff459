// Cortex-M7 (QEMU mps2-an500) run of the full-size exploration (100 bootstrap + 10,000
// episodes, default archive capacity, Explorer in .bss): completes heap-free and reproduces
// the host's checksum bit for bit.
#include "tests/explore/explore_smoke.hpp"
#include "toolchain/qemu/semihosting.h"

namespace {
curio::Explorer g_explorer;  // ~680 KB of .bss (compact archive)
}

int main() {
  using namespace curio::test;
  const SmokeResult r = run_smoke(g_explorer, kFullBootstrap, kFullEpisodes);
  curio_semihost_print("explore full: sizeof(Explorer) ");
  curio_semihost_print_u32(static_cast<uint32_t>(sizeof(curio::Explorer)));
  curio_semihost_print(", episodes ");
  curio_semihost_print_u32(static_cast<uint32_t>(r.episodes));
  curio_semihost_print(", nn queries ");
  curio_semihost_print_u32(r.nn_queries);
  curio_semihost_print(", checksum ");
  curio_semihost_print_hex32(r.checksum);
  curio_semihost_print(" (host golden ");
  curio_semihost_print_hex32(kFullChecksum);
  curio_semihost_print(")\n");
  const bool ok = r.status == curio::Status::kOk && r.episodes == kFullBootstrap + kFullEpisodes &&
                  r.checksum == kFullChecksum;
  curio_semihost_print(ok ? "PASS\n" : "FAILED\n");
  return ok ? 0 : 1;
}
