// Proves the exploration core is heap-free: this binary replaces the global allocator
// (operator new/delete and malloc/calloc/realloc/free) with counting versions, then runs a
// full 10,000-episode MGE exploration (init included) on a toy environment.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>

#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "tests/explore/toy_environment.hpp"

extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* __libc_memalign(size_t, size_t);
void __libc_free(void*);
}

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};

void note() {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1);
}
}  // namespace

extern "C" {
void* malloc(size_t n) {
  note();
  return __libc_malloc(n);
}
void* calloc(size_t n, size_t s) {
  note();
  return __libc_calloc(n, s);
}
void* realloc(void* p, size_t n) {
  note();
  return __libc_realloc(p, n);
}
void* aligned_alloc(size_t a, size_t n) {
  note();
  return __libc_memalign(a, n);
}
void free(void* p) {
  __libc_free(p);
}
}

void* operator new(size_t n) {
  note();
  if (void* p = __libc_malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](size_t n) {
  return operator new(n);
}
void* operator new(size_t n, std::align_val_t a) {
  note();
  if (void* p = __libc_memalign(static_cast<size_t>(a), n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](size_t n, std::align_val_t a) {
  return operator new(n, a);
}
void* operator new(size_t n, const std::nothrow_t&) noexcept {
  note();
  return __libc_malloc(n == 0 ? 1 : n);
}
void* operator new[](size_t n, const std::nothrow_t&) noexcept {
  note();
  return __libc_malloc(n == 0 ? 1 : n);
}
void operator delete(void* p) noexcept {
  __libc_free(p);
}
void operator delete[](void* p) noexcept {
  __libc_free(p);
}
void operator delete(void* p, size_t) noexcept {
  __libc_free(p);
}
void operator delete[](void* p, size_t) noexcept {
  __libc_free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  __libc_free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  __libc_free(p);
}
void operator delete(void* p, size_t, std::align_val_t) noexcept {
  __libc_free(p);
}
void operator delete[](void* p, size_t, std::align_val_t) noexcept {
  __libc_free(p);
}

namespace curio {
namespace {

// Kept out of the optimiser's reach so the deliberate allocations below really happen.
void* volatile g_sink = nullptr;

TEST(NoAllocation, CounterSeesDeliberateAllocations) {
  g_allocations = 0;
  g_counting = true;
  g_sink = new int(1);
  delete static_cast<int*>(g_sink);
  g_sink = std::malloc(16);
  std::free(g_sink);
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 2);
}

TEST(NoAllocation, TenThousandEpisodeMgeRunAllocatesNothing) {
  auto explorer = std::make_unique<Explorer>();  // the one allocation, before counting
  ExplorerConfig config;
  set_efr_modules(config, Algorithm::kMge);
  config.n_bootstrap = 100;
  config.n_episodes = 10000;
  config.seed = 1;

  g_allocations = 0;
  g_counting = true;
  Status init = explorer->init(config);
  Status worst = Status::kOk;
  float theta[kThetaDim];
  float outcome[kEfrOutcomeDim];
  int episodes = 0;
  while (!explorer->done() && worst == Status::kOk) {
    Status s = explorer->propose(theta);
    test::toy_outcome(theta, outcome);
    if (s == Status::kOk) s = explorer->observe(outcome);
    if (s != Status::kOk) worst = s;
    ++episodes;
  }
  g_counting = false;

  EXPECT_EQ(init, Status::kOk);
  EXPECT_EQ(worst, Status::kOk);
  EXPECT_EQ(episodes, 10100);
  EXPECT_EQ(g_allocations.load(), 0);
  EXPECT_GT(explorer->counters().nn_queries, 3000u);
}

}  // namespace
}  // namespace curio

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
