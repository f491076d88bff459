/* C half of the ZynqMP start-up (startup.S runs first): .data copied if the loader did not
   place it (LMA ≠ VMA), .bss zeroed, the C++ static constructors, main(), and its status as
   QEMU's exit status through semihosting. curio_fault reports an unexpected exception. */
#include <stdint.h>

#include "toolchain/qemu/semihosting.h"

extern uint32_t __data_start, __data_end, __data_load, __bss_start, __bss_end;
extern void (*__preinit_array_start[])(void), (*__preinit_array_end[])(void);
extern void (*__init_array_start[])(void), (*__init_array_end[])(void);

int main(void);
void curio_reset_c(void);
void curio_fault(uint32_t kind, uint32_t address);

void* __dso_handle = 0;
int __aeabi_atexit(void* object, void (*destructor)(void*), void* dso) {
  (void)object;
  (void)destructor;
  (void)dso;
  return 0;
}

/* A weak default: images without interrupt handling (the firmware tests) never enable IRQs. */
__attribute__((weak)) void curio_irq_dispatch(void) {
  curio_semihost_print("FAULT: IRQ without a handler\n");
  curio_semihost_exit(3);
}

void curio_fault(uint32_t kind, uint32_t address) {
  static const char* const kNames[8] = {
      "reset", "undefined instruction", "SVC", "prefetch abort", "data abort", "?", "IRQ", "FIQ"};
  curio_semihost_print("FAULT: unexpected exception: ");
  curio_semihost_print(kNames[kind & 7u]);
  curio_semihost_print(" near ");
  curio_semihost_print_hex32(address);
  curio_semihost_print("\n");
  curio_semihost_exit(3);
}

void curio_reset_c(void) {
  if (&__data_load != &__data_start) {
    const uint32_t* src = &__data_load;
    for (uint32_t* dst = &__data_start; dst < &__data_end;) *dst++ = *src++;
  }
  for (uint32_t* dst = &__bss_start; dst < &__bss_end;) *dst++ = 0u;
  for (void (**f)(void) = __preinit_array_start; f < __preinit_array_end; ++f) (*f)();
  for (void (**f)(void) = __init_array_start; f < __init_array_end; ++f) (*f)();
  curio_semihost_exit(main());
}
