/* LD_PRELOAD for QEMU's xlnx-zcu102 inside User-mode Linux (tests/uml/zynqmp_can_uml.sh).
   The machine always creates four 64 MiB QSPI NOR flash models (n25q512a11), and each fills
   its storage with 0xFF at start-up: 256 MiB written page by page. Inside UML every first
   touch of a page is a page fault that the UML kernel serves over ptrace, so that fill alone
   takes ~80 s there (QEMU's whole start-up takes 1 s on the host); the image never reads the
   flash. This shim turns memset(p, 0xFF, n) of a page-aligned block of at least 16 MiB into a
   private (copy-on-write) mapping of a file of 0xFF bytes, CURIO_FF_FILE: the same content,
   paged in only if read. Any other memset, or without the file, goes to the C library's. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

typedef void* (*memset_fn)(void*, int, size_t);
static memset_fn real_memset;
static int ff_fd = -2;
static size_t ff_size;

__attribute__((constructor)) static void init(void) {
  real_memset = (memset_fn)dlsym(RTLD_NEXT, "memset");
  const char* path = getenv("CURIO_FF_FILE");
  ff_fd = -1;
  if (path != NULL) {
    struct stat st;
    const int fd = open(path, O_RDONLY);
    if (fd >= 0 && fstat(fd, &st) == 0) {
      ff_fd = fd;
      ff_size = (size_t)st.st_size;
    }
  }
}

void* memset(void* p, int c, size_t n) {
  const size_t page = 4096;
  if (ff_fd >= 0 && (c & 0xFF) == 0xFF && n >= (16u << 20) && n <= ff_size &&
      ((uintptr_t)p % page) == 0 && n % page == 0 &&
      mmap(p, n, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_FIXED, ff_fd, 0) == p) {
    return p;
  }
  if (real_memset != NULL) return real_memset(p, c, n);
  volatile unsigned char* b = (volatile unsigned char*)p; /* not turned back into memset */
  for (size_t i = 0; i < n; ++i) b[i] = (unsigned char)c;
  return p;
}
