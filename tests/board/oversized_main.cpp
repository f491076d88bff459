// A deliberately sized image for the board budget (toolchain/boards/stm32h743_budget.ld):
// CURIO_BALLAST_RAM or CURIO_BALLAST_FLASH bytes of ballast in .bss or .rodata. Built just
// under the budget it links and runs; built just over it must fail to link
// (firmware.board.budget_enforced_*: the budget is enforced, not only reported).
#include <cstdint>

#if defined(CURIO_BALLAST_RAM)
uint8_t g_ballast[CURIO_BALLAST_RAM];  // .bss
#elif defined(CURIO_BALLAST_FLASH)
extern const uint8_t g_ballast[CURIO_BALLAST_FLASH];
const uint8_t g_ballast[CURIO_BALLAST_FLASH] = {1};  // .rodata
#else
#error "define CURIO_BALLAST_RAM or CURIO_BALLAST_FLASH"
#endif

// Reads the last byte, so the ballast is used (not garbage-collected) and addressable: 0.
int main() {
  const volatile uint8_t* last = &g_ballast[sizeof(g_ballast) - 1];
  return *last;
}
