/* A full disk at a chosen write, for any program (LD_PRELOAD), as SQLite's tests inject I/O
 * errors: the Nth write(2)-family call to a regular file, and every one after it, fails with
 * ENOSPC, as a disk that has just filled. Writes to terminals, pipes and sockets (stderr, where
 * the error message goes) pass. Counting is per process.
 *
 *   CURIO_ENOSPC_AT=N      fail from the Nth write to a regular file on (1 = the first);
 *                          unset or 0: fail nothing, only count
 *   CURIO_ENOSPC_COUNT=F   at exit, append the number of writes to regular files to F, one
 *                          line per process (a dry run counts the writes a command makes:
 *                          the Ns to try)
 *
 *   LD_PRELOAD=build/default/tests/common/libcurio_enospc_shim.so CURIO_ENOSPC_AT=7 curio-lab run ...
 *
 * The real calls are made with syscall(2), so the shim needs no dlsym. A short write (part of
 * the bytes) is not simulated: the failing call writes nothing. */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

static long writes_to_files;

static int is_regular(int fd) {
  struct stat st;
  return fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
}

/* 1: this write to a regular file is to fail (the disk is full from here on). */
static int disk_full(int fd) {
  if (!is_regular(fd)) return 0;
  ++writes_to_files;
  const char* at = getenv("CURIO_ENOSPC_AT");
  const long n = at ? atol(at) : 0;
  return n > 0 && writes_to_files >= n;
}

ssize_t write(int fd, const void* buf, size_t count) {
  if (disk_full(fd)) {
    errno = ENOSPC;
    return -1;
  }
  return syscall(SYS_write, fd, buf, count);
}

ssize_t pwrite(int fd, const void* buf, size_t count, off_t offset) {
  if (disk_full(fd)) {
    errno = ENOSPC;
    return -1;
  }
  return syscall(SYS_pwrite64, fd, buf, count, offset);
}
ssize_t pwrite64(int fd, const void* buf, size_t count, off_t offset)
    __attribute__((alias("pwrite")));

ssize_t writev(int fd, const struct iovec* iov, int iovcnt) {
  if (disk_full(fd)) {
    errno = ENOSPC;
    return -1;
  }
  return syscall(SYS_writev, fd, iov, iovcnt);
}

__attribute__((destructor)) static void report_count(void) {
  const char* path = getenv("CURIO_ENOSPC_COUNT");
  if (!path) return;
  const long n = writes_to_files;
  setenv("CURIO_ENOSPC_AT", "0", 1); /* the report itself always goes through */
  FILE* f = fopen(path, "a");        /* one line per process (gnuplot's too) */
  if (!f) return;
  fprintf(f, "%ld\n", n);
  fclose(f);
}
