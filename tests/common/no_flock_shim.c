/* A file system without flock(2), for any program (LD_PRELOAD): every flock fails with ENOSYS,
 * as on Lustre mounted without -o flock. The output-folder claim must then go on unlocked with a
 * warning (host_tools/common/output_folder.hpp), not refuse the run.
 *   LD_PRELOAD=build/default/tests/common/libcurio_no_flock_shim.so curio-lab run ... */
#include <errno.h>
#include <sys/file.h>

int flock(int fd, int operation) {
  (void)fd;
  (void)operation;
  errno = ENOSYS;
  return -1;
}
