// The training schedule: plain-VAE warm-up, β ramp, capacity ramp, learning-rate shape.
#include "host_tools/train/recipe.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

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

// The curriculum's ball spread: constant without a ramp; with one, linear from ball_spread to
// ball_spread_to in steps of 1/32 (each step re-renders the set, so there are at most 32).
TEST(Schedule, BallSpreadRampsInSteps) {
  Recipe r;
  EXPECT_EQ(schedule_at(r, 0).ball_spread, 1.0);
  r.ball_spread = 0.25;
  EXPECT_EQ(schedule_at(r, 5000).ball_spread, 0.25);
  r.ball_spread = 0.0;
  r.ball_spread_to = 1.0;
  r.ball_spread_iters = 3200;
  EXPECT_EQ(schedule_at(r, 0).ball_spread, 0.0);
  EXPECT_EQ(schedule_at(r, 49).ball_spread, 0.0);
  EXPECT_EQ(schedule_at(r, 50).ball_spread, 1.0 / 32);  // 50/3200 = 0.5/32 rounds up
  EXPECT_EQ(schedule_at(r, 1600).ball_spread, 0.5);
  EXPECT_EQ(schedule_at(r, 3200).ball_spread, 1.0);
  EXPECT_EQ(schedule_at(r, 9000).ball_spread, 1.0);
  int steps = 0;
  for (int64_t it = 1; it <= 3200; ++it)
    steps += schedule_at(r, it).ball_spread != schedule_at(r, it - 1).ball_spread;
  EXPECT_EQ(steps, 32);
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

TEST(Schedule, EncoderFreezeRunsToTheEndUnlessGivenAnEnd) {
  Recipe r;
  EXPECT_FALSE(encoder_frozen_at(r, 0));  // no freeze by default
  EXPECT_FALSE(encoder_frozen_at(r, 100000));
  r.freeze_encoder_from = 1000;           // --freeze-encoder-from alone: to the end
  EXPECT_FALSE(encoder_frozen_at(r, 999));
  EXPECT_TRUE(encoder_frozen_at(r, 1000));
  EXPECT_TRUE(encoder_frozen_at(r, 1000000));
  r.freeze_encoder_to = 3000;             // a window
  EXPECT_TRUE(encoder_frozen_at(r, 2999));
  EXPECT_FALSE(encoder_frozen_at(r, 3000));
}

TEST(LatentStages, ParseAndGiveTheTrainedCountAtEachIteration) {
  Recipe r;
  EXPECT_EQ(trained_latents(r, 0), 10);  // no stages: all latents from the start
  r.latent_stages = parse_latent_stages("0:2,1000:4,3000:10");
  ASSERT_EQ(r.latent_stages.size(), 3u);
  EXPECT_EQ(trained_latents(r, 0), 2);
  EXPECT_EQ(trained_latents(r, 999), 2);
  EXPECT_EQ(trained_latents(r, 1000), 4);
  EXPECT_EQ(trained_latents(r, 2999), 4);
  EXPECT_EQ(trained_latents(r, 3000), 10);
  EXPECT_TRUE(parse_latent_stages("").empty());
  r.latent_stages = parse_latent_stages("0:10,500:6");  // counts may fall (pruning)
  EXPECT_EQ(trained_latents(r, 499), 10);
  EXPECT_EQ(trained_latents(r, 500), 6);
}

TEST(LatentStages, RefuseMalformedOrUnorderedText) {
  for (const char* bad : {"2", "0:2,", "0:x", "0:2,100", "5:2", "0:0", "0:11",
                          "0:2,0:4", "0:2,100:4:1"})
    EXPECT_THROW(parse_latent_stages(bad), std::invalid_argument) << bad;
}

TEST(Recipe, RoundTripsThroughJson) {
  Recipe r;
  r.warmup = 123;
  r.seed = 99;
  r.capacity_min = 1.5;
  r.latent_stages = {{0, 2}, {500, 4}};
  r.init = "torch-default";
  r.freeze_decoder_too = true;
  r.recycle_every = 250;
  r.recycle_threshold = 0.05;
  r.prune_by = "recon";
  r.recycle_outgoing_scale = 0.3;
  r.recycle_decoder_too = true;
  r.revive_at = 7;
  r.revive_fresh_decoder = true;
  r.freeze_active_readout = true;
  r.ball_spread = 0.25;
  r.ball_spread_to = 0.75;
  r.ball_spread_iters = 4000;
  r.scenes_file = "runs/x_scenes.csv";
  const Recipe back = recipe_from_json(to_json(r));
  EXPECT_EQ(back.warmup, 123);
  EXPECT_EQ(back.seed, 99u);
  EXPECT_EQ(back.capacity_min, 1.5);
  EXPECT_EQ(back.latent_stages, r.latent_stages);
  EXPECT_EQ(back.init, "torch-default");
  EXPECT_TRUE(back.freeze_decoder_too);
  EXPECT_EQ(back.recycle_every, 250);
  EXPECT_EQ(back.recycle_threshold, 0.05);
  EXPECT_EQ(back.prune_by, "recon");
  EXPECT_EQ(back.recycle_outgoing_scale, 0.3);
  EXPECT_TRUE(back.recycle_decoder_too);
  EXPECT_EQ(back.revive_at, 7);
  EXPECT_TRUE(back.revive_fresh_decoder);
  EXPECT_TRUE(back.freeze_active_readout);
  EXPECT_EQ(back.ball_spread, 0.25);
  EXPECT_EQ(back.ball_spread_to, 0.75);
  EXPECT_EQ(back.ball_spread_iters, 4000);
  EXPECT_EQ(back.scenes_file, "runs/x_scenes.csv");
  EXPECT_EQ(to_json(back), to_json(r));
}

}  // namespace
}  // namespace curio::train
