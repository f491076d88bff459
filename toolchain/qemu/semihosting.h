/* Minimal ARM semihosting for bare-metal tests under QEMU (-semihosting-config enable=on):
   text to the host's console, elapsed ticks, and an exit status that becomes QEMU's. */
#pragma once
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

void curio_semihost_print(const char* text);     /* NUL-terminated */
void curio_semihost_print_u32(uint32_t value);   /* decimal */
void curio_semihost_print_hex32(uint32_t value); /* 0x%08x */
/* SYS_ELAPSED: ticks since start (0 if unsupported). QEMU counts nanoseconds of virtual time;
   under -icount shift=0 one guest instruction is one nanosecond, so differences are exact
   instruction counts (including the few instructions of the call itself). */
uint64_t curio_semihost_elapsed(void);
void curio_semihost_exit(int status) __attribute__((noreturn));

#ifdef __cplusplus
}
#endif
