// Preloaded into linux.uml by tests/uml/run-in-uml.sh: lets User-mode Linux boot on hosts whose
// XSAVE area is larger than the buffer UML hands to ptrace.
//
// Why: UML runs each guest process as a host process it drives with ptrace, and at every switch
// it saves and restores the FPU state with PTRACE_GETREGSET / PTRACE_SETREGSET (NT_X86_XSTATE).
// The host kernel copies out a truncated state on GET, but accepts a SET only from one whole
// XSAVE buffer of exactly its own size (anything else is EFAULT). Debian 12's UML 6.1 passes
// 2,688 bytes (x87/SSE, AVX, AVX-512); on a Xeon with AMX under host kernel 6.18 the kernel's
// size is 11,008 bytes (PKRU and the AMX tile registers follow), so UML's very first SET fails:
// "userspace - ptrace set fp regs failed, errno = 14" on the console, and UML never boots.
//
// What this does: a SET whose buffer is shorter than the kernel's reads the tracee's whole current
// state, lays UML's bytes over its start and sets the whole buffer. The bytes past UML's buffer
// stay what the tracee already holds: PKRU and AMX state, which no guest process can touch (UML
// offers no syscall that enables them). Every other ptrace call, and every SET on a host whose
// size UML already matches, goes straight to glibc's ptrace: this file changes nothing there.
// Single-threaded use only (UML issues ptrace from its one kernel thread): one static buffer.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <elf.h>
#include <errno.h>
#include <stdarg.h>
#include <string.h>
#include <sys/ptrace.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

// Largest XSAVE area the architecture defines today is 11,008 bytes (AMX); room to spare.
static unsigned char whole_state[65536] __attribute__((aligned(64)));
static size_t kernel_size;  // the host kernel's NT_X86_XSTATE size, learnt at the first SET

static long raw_ptrace(long request, pid_t pid, void* addr, void* data) {
  return syscall(SYS_ptrace, request, pid, addr, data);
}

long ptrace(enum __ptrace_request request, ...) {
  va_list args;
  va_start(args, request);
  pid_t pid = va_arg(args, pid_t);
  void* addr = va_arg(args, void*);
  void* data = va_arg(args, void*);
  va_end(args);

  if (request == PTRACE_SETREGSET && (long)addr == NT_X86_XSTATE && data != NULL) {
    const struct iovec* theirs = (const struct iovec*)data;
    if (kernel_size == 0 || theirs->iov_len < kernel_size) {
      struct iovec whole = {whole_state, sizeof whole_state};
      if (raw_ptrace(PTRACE_GETREGSET, pid, addr, &whole) != 0) return -1;
      kernel_size = whole.iov_len;  // the kernel shortens iov_len to its own size
      if (theirs->iov_len < kernel_size) {
        memcpy(whole_state, theirs->iov_base, theirs->iov_len);
        return raw_ptrace(PTRACE_SETREGSET, pid, addr, &whole);
      }
    }
  }
  static long (*glibc_ptrace)(enum __ptrace_request, ...);
  if (glibc_ptrace == NULL) {
    glibc_ptrace = (long (*)(enum __ptrace_request, ...))dlsym(RTLD_NEXT, "ptrace");
    if (glibc_ptrace == NULL) {
      errno = ENOSYS;
      return -1;
    }
  }
  return glibc_ptrace(request, pid, addr, data);
}
