#include "host_tools/train/allocator_tuning.hpp"

#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace curio::train {

std::string keep_freed_memory_in_process() {
#if defined(__GLIBC__)
  for (const char* env : {"MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_", "MALLOC_TOP_PAD_"})
    if (std::getenv(env) != nullptr) return std::string("allocator: left as set by ") + env;
  constexpr int kMiB = 1 << 20;
  const bool ok = mallopt(M_MMAP_THRESHOLD, 256 * kMiB) == 1 &&
                  mallopt(M_TRIM_THRESHOLD, 1024 * kMiB) == 1 &&
                  mallopt(M_TOP_PAD, 256 * kMiB) == 1;
  return ok ? "allocator: glibc, freed tensor memory kept in the process (mmap threshold 256 MiB)"
            : "allocator: glibc refused the mallopt settings (defaults in use)";
#else
  return "";
#endif
}

}  // namespace curio::train
