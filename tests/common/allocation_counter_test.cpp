// The allocation counter sees every kind of allocation, only while counting and only in the
// thread that counts.
#include "tests/common/allocation_counter.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <thread>

namespace curio::test {
namespace {

// Kept out of the optimiser's reach so the deliberate allocations really happen.
void* volatile g_sink = nullptr;

TEST(AllocationCounter, CountsEveryAllocationFunction) {
  start_counting_allocations();
  g_sink = ::operator new(8);
  ::operator delete(g_sink);
  g_sink = ::operator new[](8);
  ::operator delete[](g_sink);
  g_sink = ::operator new (64, std::align_val_t{64});
  ::operator delete (g_sink, std::align_val_t{64});
  g_sink = ::operator new(8, std::nothrow);
  ::operator delete(g_sink);
  g_sink = std::malloc(16);
  g_sink = std::realloc(g_sink, 32);
  std::free(g_sink);
  g_sink = std::calloc(4, 4);
  std::free(g_sink);
  g_sink = std::aligned_alloc(64, 64);
  std::free(g_sink);
  EXPECT_EQ(stop_counting_allocations(), 8);
}

TEST(AllocationCounter, CountsNothingWhenStoppedAndStartsFromZero) {
  start_counting_allocations();
  g_sink = std::malloc(16);
  EXPECT_EQ(stop_counting_allocations(), 1);
  std::free(g_sink);  // frees are never counted
  g_sink = std::malloc(16);
  std::free(g_sink);
  EXPECT_EQ(counted_allocations(), 1);
  start_counting_allocations();
  EXPECT_EQ(stop_counting_allocations(), 0);
}

TEST(AllocationCounter, OtherThreadsDoNotCount) {
  std::atomic<int> step{0};
  std::thread other([&] {
    while (step.load() != 1) std::this_thread::yield();
    g_sink = std::malloc(16);  // counted in neither thread
    std::free(g_sink);
    step = 2;
  });  // creating the thread allocates, before counting starts
  start_counting_allocations();
  step = 1;
  while (step.load() != 2) std::this_thread::yield();
  EXPECT_EQ(stop_counting_allocations(), 0);
  other.join();
}

}  // namespace
}  // namespace curio::test
