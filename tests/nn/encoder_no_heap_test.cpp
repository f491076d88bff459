// The firmware encoder allocates nothing: every operator new / malloc / calloc / realloc
// in this binary is counted, and encode() must leave the count unchanged. The first tests
// prove the counter sees each kind of allocation.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "firmware/nn/encoder.hpp"
#include "tests/nn/synthetic_firmware_model.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* malloc(size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
void* calloc(size_t n, size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(n, size);
}
void* realloc(void* p, size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, n);
}
}

void* operator new(size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = __libc_malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](size_t n) {
  return operator new(n);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, size_t) noexcept {
  std::free(p);
}

namespace curio::nn {
namespace {

// Static storage like on the controller; constructing it allocates nothing either.
Encoder g_encoder(testing::synthetic_firmware_model());
uint8_t g_frame[kImageBytes];

TEST(EncoderNoHeap, CounterSeesOperatorNew) {
  const long before = g_allocations.load();
  void* p = ::operator new(64);
  EXPECT_EQ(g_allocations.load(), before + 1);
  ::operator delete(p);
}

TEST(EncoderNoHeap, CounterSeesMalloc) {
  const long before = g_allocations.load();
  void* volatile p = std::malloc(64);
  EXPECT_EQ(g_allocations.load(), before + 1);
  std::free(p);
}

TEST(EncoderNoHeap, EncodeAllocatesNothing) {
  for (int i = 0; i < kImageBytes; ++i) g_frame[i] = static_cast<uint8_t>((i * 37) & 0xFF);
  float mu[kLatents];
  float log_var[kLatents];
  const long before = g_allocations.load();
  Status s1 = g_encoder.encode(g_frame, mu);
  Status s2 = g_encoder.encode(g_frame, mu, log_var);
  const long after = g_allocations.load();
  EXPECT_EQ(s1, Status::kOk);
  EXPECT_EQ(s2, Status::kOk);
  EXPECT_EQ(after, before) << "encode() allocated " << (after - before) << " times";
}

}  // namespace
}  // namespace curio::nn
