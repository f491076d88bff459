// The training schedule: plain-VAE warm-up, β ramp, capacity ramp, learning-rate shape.
#include "train/recipe.hpp"

#include <gtest/gtest.h>

namespace curio::train {
namespace {

TEST(Schedule, WarmsUpAsAPlainVaeThenRampsCapacityFromTheWarmupsEnd) {
  Recipe r;
  r.warmup = 1000;
  r.capacity_iters = 2000;
  r.capacity_max = 12.0;
  EXPECT_EQ(schedule_at(r, 0).beta, 1.0);
  EXPECT_EQ(schedule_at(r, 999).capacity, 0.0);
  EXPECT_EQ(schedule_at(r, 1000).beta, 150.0);
  EXPECT_DOUBLE_EQ(schedule_at(r, 2000).capacity, 6.0);
  EXPECT_DOUBLE_EQ(schedule_at(r, 3000).capacity, 12.0);
  EXPECT_DOUBLE_EQ(schedule_at(r, 9000).capacity, 12.0);
}

TEST(Schedule, RampsBetaFromOne) {
  Recipe r;
  r.beta_ramp = 100;
  EXPECT_DOUBLE_EQ(schedule_at(r, 0).beta, 1.0);
  EXPECT_DOUBLE_EQ(schedule_at(r, 50).beta, 75.5);
  EXPECT_DOUBLE_EQ(schedule_at(r, 100).beta, 150.0);
}

TEST(Schedule, VaeHasBetaOneAndNoCapacity) {
  Recipe r;
  r.model = "vae";
  EXPECT_EQ(schedule_at(r, 5000).beta, 1.0);
  EXPECT_EQ(schedule_at(r, 5000).capacity, 0.0);
}

TEST(Schedule, LearningRateWarmsUpAndDecays) {
  Recipe r;
  r.iterations = 1000;
  r.lr = 1e-3;
  r.lr_warmup = 10;
  r.lr_decay_from = 500;
  r.lr_final = 1e-4;
  EXPECT_DOUBLE_EQ(schedule_at(r, 0).lr, 1e-4);
  EXPECT_DOUBLE_EQ(schedule_at(r, 9).lr, 1e-3);
  EXPECT_DOUBLE_EQ(schedule_at(r, 500).lr, 1e-3);
  EXPECT_NEAR(schedule_at(r, 1000).lr, 1e-4, 1e-12);
}

TEST(Recipe, RoundTripsThroughJson) {
  Recipe r;
  r.warmup = 123;
  r.seed = 99;
  r.capacity_min = 1.5;
  const Recipe back = recipe_from_json(to_json(r));
  EXPECT_EQ(back.warmup, 123);
  EXPECT_EQ(back.seed, 99u);
  EXPECT_EQ(back.capacity_min, 1.5);
  EXPECT_EQ(to_json(back), to_json(r));
}

}  // namespace
}  // namespace curio::train
