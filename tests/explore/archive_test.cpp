#include "firmware/explore/archive.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace curio {
namespace {

TEST(Archive, StoresThetaAndOutcomeInOrder) {
  auto a = std::make_unique<Archive>();
  ASSERT_EQ(a->reset(3), Status::kOk);
  float theta[kThetaDim];
  for (int e = 0; e < 5; ++e) {
    for (int k = 0; k < kThetaDim; ++k) theta[k] = static_cast<float>(e * 100 + k);
    const float outcome[3] = {static_cast<float>(e), -1.0f * static_cast<float>(e), 0.5f};
    ASSERT_EQ(a->append(theta, outcome), Status::kOk);
  }
  EXPECT_EQ(a->size(), 5);
  EXPECT_EQ(a->outcome_dim(), 3);
  EXPECT_EQ(a->theta(3)[7], 307.0f);
  EXPECT_EQ(a->outcome(4, 1), -4.0f);
  EXPECT_EQ(a->outcome_column(0)[2], 2.0f);
}

TEST(Archive, RejectsBadDimensionsAndNulls) {
  auto a = std::make_unique<Archive>();
  EXPECT_EQ(a->reset(0), Status::kInvalidArgument);
  EXPECT_EQ(a->reset(kMaxOutcomeDim + 1), Status::kInvalidArgument);
  const float theta[kThetaDim] = {};
  const float outcome[1] = {0.0f};
  EXPECT_EQ(a->append(theta, outcome), Status::kInvalidArgument);  // before reset
  ASSERT_EQ(a->reset(1), Status::kOk);
  EXPECT_EQ(a->append(nullptr, outcome), Status::kInvalidArgument);
  EXPECT_EQ(a->append(theta, nullptr), Status::kInvalidArgument);
  EXPECT_EQ(a->size(), 0);
}

TEST(Archive, ReportsFullAndCountsRejections) {
  auto a = std::make_unique<Archive>();
  ASSERT_EQ(a->reset(1), Status::kOk);
  const float theta[kThetaDim] = {};
  const float outcome[1] = {1.0f};
  for (int i = 0; i < Archive::kCapacity; ++i) ASSERT_EQ(a->append(theta, outcome), Status::kOk);
  EXPECT_TRUE(a->full());
  EXPECT_EQ(a->append(theta, outcome), Status::kFull);
  EXPECT_EQ(a->append(theta, outcome), Status::kFull);
  EXPECT_EQ(a->size(), Archive::kCapacity);
  EXPECT_EQ(a->rejected_full(), 2u);
}

}  // namespace
}  // namespace curio
