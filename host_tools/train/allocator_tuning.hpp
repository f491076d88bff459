// Keeps LibTorch's large, short-lived tensor buffers inside the process.
//
// glibc serves every allocation above M_MMAP_THRESHOLD (128 KiB at start) with a fresh mmap and
// returns freed heap tops to the kernel above M_TRIM_THRESHOLD; a training step allocates and
// frees activations of 0.5–4 MiB many times, so the kernel zeroes and maps fresh pages every
// step. Measured on this 2-core machine (batch 32, one thread, 400 iterations): 7.3 it/s with
// glibc's defaults, 17.8 it/s with the settings below, identical losses bit for bit
// (`tests/train/bench_allocator.sh` repeats the measurement). Host tools only.
#pragma once
#include <string>

namespace curio::train {

// Raises the mmap and trim thresholds (256 MiB / 1 GiB) and the heap top pad (256 MiB), unless
// the user set MALLOC_*_ environment variables. Returns a one-line description for the log
// ("" where the C library is not glibc and nothing was changed).
std::string keep_freed_memory_in_process();

}  // namespace curio::train
