// Counts the calling thread's heap allocations, for the tests that prove code allocates
// nothing. A binary that links allocation_counter.cpp (CMake: curio_allocation_counter) has
// its global allocator replaced: operator new in every form, malloc, calloc, realloc and
// aligned_alloc are counted while their thread counts; frees never are. Per thread, so that
// a simulated arm or any other helper thread does not count.
#pragma once

namespace curio::test {

// Starts counting the calling thread's allocations, from zero.
void start_counting_allocations();

// Stops counting; the calling thread's allocations since start_counting_allocations().
long stop_counting_allocations();

// The calling thread's allocations counted so far (while counting or after it stopped).
long counted_allocations();

}  // namespace curio::test
