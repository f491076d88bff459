// The firmware encoder allocates nothing: this binary counts heap allocations
// (tests/common/allocation_counter.hpp), and encode() must make none. The first tests prove
// the counter sees each kind of allocation.
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>

#include "firmware/nn/encoder.hpp"
#include "tests/common/allocation_counter.hpp"
#include "tests/nn/synthetic_firmware_model.hpp"

namespace curio::nn {
namespace {

// Static storage like on the controller; constructing it allocates nothing either.
Encoder g_encoder(testing::synthetic_firmware_model());
uint8_t g_frame[kImageBytes];

TEST(EncoderNoHeap, CounterSeesOperatorNew) {
  curio::test::start_counting_allocations();
  void* p = ::operator new(64);
  EXPECT_EQ(curio::test::stop_counting_allocations(), 1);
  ::operator delete(p);
}

TEST(EncoderNoHeap, CounterSeesMalloc) {
  curio::test::start_counting_allocations();
  void* volatile p = std::malloc(64);
  EXPECT_EQ(curio::test::stop_counting_allocations(), 1);
  std::free(p);
}

TEST(EncoderNoHeap, EncodeAllocatesNothing) {
  for (int i = 0; i < kImageBytes; ++i) g_frame[i] = static_cast<uint8_t>((i * 37) & 0xFF);
  float mu[kLatents];
  float log_var[kLatents];
  curio::test::start_counting_allocations();
  Status s1 = g_encoder.encode(g_frame, mu);
  Status s2 = g_encoder.encode(g_frame, mu, log_var);
  const long allocations = curio::test::stop_counting_allocations();
  EXPECT_EQ(s1, Status::kOk);
  EXPECT_EQ(s2, Status::kOk);
  EXPECT_EQ(allocations, 0) << "encode() allocated " << allocations << " times";
}

}  // namespace
}  // namespace curio::nn
