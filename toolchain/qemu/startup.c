/* Bare-metal start for Cortex-M7 test images under QEMU: vector table at address 0, reset
   handler that enables the FPU before any float instruction, copies .data, zeroes .bss, runs
   the C++ static constructors, calls main() and exits through semihosting with its status. */
#include <stdint.h>

#include "toolchain/qemu/semihosting.h"

extern uint32_t __data_start, __data_end, __data_load, __bss_start, __bss_end, __stack_top;
extern void (*__preinit_array_start[])(void), (*__preinit_array_end[])(void);
extern void (*__init_array_start[])(void), (*__init_array_end[])(void);

int main(void);
void curio_reset_handler(void);
void curio_reset_c(void);

/* Static destructors never run (main's return ends the program); register nothing. */
void* __dso_handle = 0;
int __aeabi_atexit(void* object, void (*destructor)(void*), void* dso) {
  (void)object;
  (void)destructor;
  (void)dso;
  return 0;
}

static void fault_handler(void) {
  curio_semihost_print("FAULT: unexpected exception\n");
  curio_semihost_exit(3);
}

__attribute__((section(".vectors"), used)) void (*const curio_vectors[16])(void) = {
    (void (*)(void))(&__stack_top), /* initial SP */
    curio_reset_handler,            /* reset */
    fault_handler,                  /* NMI */
    fault_handler,                  /* HardFault */
    fault_handler,                  /* MemManage */
    fault_handler,                  /* BusFault */
    fault_handler,                  /* UsageFault */
    0,                              /* reserved */
    0,                              /* reserved */
    0,                              /* reserved */
    0,                              /* reserved */
    fault_handler,                  /* SVCall */
    fault_handler,                  /* DebugMon */
    0,                              /* reserved */
    fault_handler,                  /* PendSV */
    fault_handler,                  /* SysTick */
};

/* Naked: nothing may touch the FPU (the compiler can use it for copies) before CPACR is set. */
__attribute__((naked, noreturn)) void curio_reset_handler(void) {
  __asm__ volatile(
      "ldr r0, =0xE000ED88\n" /* CPACR */
      "ldr r1, [r0]\n"
      "orr r1, r1, #(0xF << 20)\n" /* CP10, CP11 full access */
      "str r1, [r0]\n"
      "dsb\n"
      "isb\n"
      "b curio_reset_c\n");
}

void curio_reset_c(void) {
  const uint32_t* src = &__data_load;
  for (uint32_t* dst = &__data_start; dst < &__data_end;) *dst++ = *src++;
  for (uint32_t* dst = &__bss_start; dst < &__bss_end;) *dst++ = 0u;
  for (void (**f)(void) = __preinit_array_start; f < __preinit_array_end; ++f) (*f)();
  for (void (**f)(void) = __init_array_start; f < __init_array_end; ++f) (*f)();
  curio_semihost_exit(main());
}
