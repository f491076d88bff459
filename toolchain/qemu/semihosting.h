/* Minimal ARM semihosting for bare-metal tests under QEMU (-semihosting-config enable=on):
   text to the host's console, the command line and an exit status that becomes QEMU's. */
#pragma once
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

void curio_semihost_print(const char* text);     /* NUL-terminated */
void curio_semihost_print_u32(uint32_t value);   /* decimal */
void curio_semihost_print_hex32(uint32_t value); /* 0x%08x */
/* The command line (QEMU: -semihosting-config ...,arg=A,arg=B gives "A B"), NUL-terminated
   in buf; returns its length, or -1 when there is none or it does not fit. */
int curio_semihost_cmdline(char* buf, uint32_t size);
void curio_semihost_exit(int status) __attribute__((noreturn));

#ifdef __cplusplus
}
#endif
