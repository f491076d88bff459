// firmware.board.stm32h743 (Cortex-M7, QEMU mps2-an500, linked against the STM32H743 budget
// toolchain/boards/stm32h743_budget.ld: 2 MiB flash, 1 MiB RAM): the deployable firmware at
// full size in one image — the Explorer with the 10,400-episode compact archive, the
// Controller with its CANopen master, ISO-TP receiver and frame buffers, and the int8 β-VAE
// encoder with its weights and arena — plus the in-image bus and fake arm of the QEMU
// controller test (tests/app/qemu_app/), which stand in for the CAN driver and the arm.
// It runs the controller scenario (must print the host's checksums, as
// firmware.app.qemu_controller does with its 128-entry archive) and one encoder call.
// That the image links proves the budget; the build prints the per-component table
// (toolchain/boards/memory_summary.py, docs/deploy.md "Memory budget").
#include <cmath>
#include <cstdint>

#include "firmware/nn/encoder.hpp"
#include "firmware/nn/models/beta_vae_weights.hpp"
#include "tests/app/qemu_app/controller_run.hpp"
#include "toolchain/qemu/semihosting.h"

namespace {

curio::test::ControllerScenario g_scenario;  // Explorer + Controller + bus + fake arm: .bss
curio::nn::Encoder g_encoder(curio::nn::beta_vae::kEncoderModel);
uint8_t g_frame[curio::nn::kImageBytes];

void check(bool ok, const char* what, int* failures) {
  if (ok) return;
  curio_semihost_print("FAIL: ");
  curio_semihost_print(what);
  curio_semihost_print("\n");
  ++*failures;
}

}  // namespace

int main() {
  using namespace curio::test;
  const ScenarioResult r = g_scenario.run();
  curio_semihost_print("board stm32h743 budget image: archive capacity ");
  curio_semihost_print_u32(static_cast<uint32_t>(curio::kArchiveCapacity));
  curio_semihost_print(", sizeof(Explorer) ");
  curio_semihost_print_u32(static_cast<uint32_t>(sizeof(curio::Explorer)));
  curio_semihost_print(", episodes ");
  curio_semihost_print_u32(static_cast<uint32_t>(r.episodes));
  curio_semihost_print(", archive checksum ");
  curio_semihost_print_hex32(r.archive_checksum);
  curio_semihost_print(" (host golden ");
  curio_semihost_print_hex32(kControllerArchiveChecksum);
  curio_semihost_print(")\n");

  int failures = scenario_failures(r, g_scenario);
  check(failures == 0, "the controller run was not clean", &failures);
  check(r.archive_checksum == kControllerArchiveChecksum, "archive checksum", &failures);
  check(r.wire_checksum == kControllerWireChecksum, "wire checksum", &failures);
  check(r.hand_checksum == kControllerHandChecksum, "hand checksum", &failures);

  for (int i = 0; i < curio::nn::kImageBytes; ++i) g_frame[i] = static_cast<uint8_t>(i * 37);
  float mu[curio::nn::kLatents] = {};
  const bool encoded = g_encoder.encode(g_frame, mu) == curio::nn::Status::kOk;
  check(encoded, "encoder call", &failures);
  for (float m : mu) check(std::isfinite(m), "encoder output not finite", &failures);

  curio_semihost_print(failures == 0 ? "PASS\n" : "FAILED\n");
  return failures == 0 ? 0 : 1;
}
