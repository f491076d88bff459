#include "toolchain/qemu/semihosting.h"

enum {
  kSysWrite0 = 0x04,
  kSysGetCmdline = 0x15,
  kSysExitExtended = 0x20,
  kAdpStoppedApplicationExit = 0x20026,
};

static int semihost_call(int op, const void* arg) {
  register int r0 __asm__("r0") = op;
  register const void* r1 __asm__("r1") = arg;
  /* M profile: BKPT 0xAB. A and R profiles (the ZynqMP images): SVC 0xAB in Thumb state,
     SVC 0x123456 in ARM state. */
#if defined(__ARM_ARCH_PROFILE) && __ARM_ARCH_PROFILE == 'M'
  __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
#elif defined(__thumb__)
  __asm__ volatile("svc 0xAB" : "+r"(r0) : "r"(r1) : "memory");
#else
  __asm__ volatile("svc 0x123456" : "+r"(r0) : "r"(r1) : "memory");
#endif
  return r0;
}

void curio_semihost_print(const char* text) {
  semihost_call(kSysWrite0, text);
}

void curio_semihost_print_u32(uint32_t value) {
  char buf[11];
  int i = 10;
  buf[i] = '\0';
  do {
    buf[--i] = (char)('0' + value % 10u);
    value /= 10u;
  } while (value != 0u);
  curio_semihost_print(&buf[i]);
}

void curio_semihost_print_hex32(uint32_t value) {
  static const char kDigits[] = "0123456789abcdef";
  char buf[11] = {'0', 'x'};
  for (int i = 0; i < 8; ++i) buf[2 + i] = kDigits[(value >> (28 - 4 * i)) & 0xFu];
  buf[10] = '\0';
  curio_semihost_print(buf);
}

int curio_semihost_cmdline(char* buf, uint32_t size) {
  uint32_t block[2] = {(uint32_t)(uintptr_t)buf, size};
  if (size == 0u || semihost_call(kSysGetCmdline, block) != 0) return -1;
  return (int)block[1];
}

void curio_semihost_exit(int status) {
  const uint32_t block[2] = {kAdpStoppedApplicationExit, (uint32_t)status};
  semihost_call(kSysExitExtended, block);
  for (;;) {
  }
}
