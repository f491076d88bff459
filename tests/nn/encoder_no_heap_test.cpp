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

// encode_batch: the same outputs as encode() image by image, nothing allocated; a corrupt
// model stops it at the first image with *done saying how many were encoded.
uint8_t g_frames[3 * kImageBytes];

TEST(EncoderNoHeap, EncodeBatchGivesEncodesOutputsAndAllocatesNothing) {
  for (int i = 0; i < 3 * kImageBytes; ++i) g_frames[i] = static_cast<uint8_t>((i * 53 + i / 999) & 0xFF);
  float mu[3 * kLatents], log_var[3 * kLatents];
  int32_t done = -1;
  curio::test::start_counting_allocations();
  const Status s = g_encoder.encode_batch(g_frames, 3, mu, log_var, &done);
  const long allocations = curio::test::stop_counting_allocations();
  ASSERT_EQ(s, Status::kOk);
  EXPECT_EQ(done, 3);
  EXPECT_EQ(allocations, 0);
  for (int i = 0; i < 3; ++i) {
    float m[kLatents], lv[kLatents];
    ASSERT_EQ(g_encoder.encode(g_frames + i * kImageBytes, m, lv), Status::kOk);
    for (int j = 0; j < kLatents; ++j) {
      EXPECT_EQ(mu[i * kLatents + j], m[j]) << i << " z" << j;
      EXPECT_EQ(log_var[i * kLatents + j], lv[j]) << i << " z" << j;
    }
  }
  EXPECT_EQ(g_encoder.encode_batch(nullptr, 0, nullptr), Status::kOk);  // nothing to do
}

TEST(EncoderNoHeap, EncodeBatchStopsAtTheFirstFailure) {
  EncoderModel broken = testing::synthetic_firmware_model();
  broken.latent.scale = nullptr;  // the latent layer refuses to run
  static Encoder encoder(broken);
  float mu[3 * kLatents];
  int32_t done = -1;
  EXPECT_NE(encoder.encode_batch(g_frames, 3, mu, nullptr, &done), Status::kOk);
  EXPECT_EQ(done, 0);
  EXPECT_EQ(encoder.faults(), 1u);
}

}  // namespace
}  // namespace curio::nn
