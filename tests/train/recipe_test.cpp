// The training schedule: plain-VAE warm-up, β ramp, capacity ramp, learning-rate shape.
#include "host_tools/vae/recipe.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include <nlohmann/json.hpp>

namespace curio::train {
namespace {

TEST(Schedule, WarmsUpAsAPlainVaeThenRampsCapacityFromTheWarmupsEnd) {
  Recipe r;
  r.trial.warmup = 1000;
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
  r.trial.beta_ramp = 100;
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
  r.trial.lr_warmup = 10;
  r.trial.lr_decay_from = 500;
  r.trial.lr_final = 1e-4;
  EXPECT_DOUBLE_EQ(schedule_at(r, 0).lr, 1e-4);
  EXPECT_DOUBLE_EQ(schedule_at(r, 9).lr, 1e-3);
  EXPECT_DOUBLE_EQ(schedule_at(r, 500).lr, 1e-3);
  EXPECT_NEAR(schedule_at(r, 1000).lr, 1e-4, 1e-12);
}

TEST(Schedule, EncoderFreezeRunsToTheEndUnlessGivenAnEnd) {
  Recipe r;
  EXPECT_FALSE(encoder_frozen_at(r.trial, 0));  // no freeze by default
  EXPECT_FALSE(encoder_frozen_at(r.trial, 100000));
  r.trial.freeze_encoder_from = 1000;  // --freeze-encoder-from alone: to the end
  EXPECT_FALSE(encoder_frozen_at(r.trial, 999));
  EXPECT_TRUE(encoder_frozen_at(r.trial, 1000));
  EXPECT_TRUE(encoder_frozen_at(r.trial, 1000000));
  r.trial.freeze_encoder_to = 3000;  // a window
  EXPECT_TRUE(encoder_frozen_at(r.trial, 2999));
  EXPECT_FALSE(encoder_frozen_at(r.trial, 3000));
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
  for (const char* bad :
       {"2", "0:2,", "0:x", "0:2,100", "5:2", "0:0", "0:11", "0:2,0:4", "0:2,100:4:1"})
    EXPECT_THROW(parse_latent_stages(bad), std::invalid_argument) << bad;
}

TEST(Recipe, RoundTripsThroughJson) {
  Recipe r;
  r.trial.warmup = 123;
  r.seed = 99;
  r.capacity_min = 1.5;
  r.latent_stages = {{0, 2}, {500, 4}};
  r.trial.init = "torch-default";
  r.trial.freeze_decoder_too = true;
  r.trial.recycle_every = 250;
  r.trial.recycle_threshold = 0.05;
  r.trial.prune_by = "recon";
  r.trial.recycle_outgoing_scale = 0.3;
  r.trial.recycle_decoder_too = true;
  r.trial.revive_at = 7;
  r.trial.revive_fresh_decoder = true;
  r.trial.freeze_active_readout = true;
  r.ball_spread = 0.25;
  r.ball_spread_to = 0.75;
  r.ball_spread_iters = 4000;
  r.scenes_file = "runs/x_scenes.csv";
  const Recipe back = recipe_from_json(to_json(r));
  EXPECT_EQ(back.trial.warmup, 123);
  EXPECT_EQ(back.seed, 99u);
  EXPECT_EQ(back.capacity_min, 1.5);
  EXPECT_EQ(back.latent_stages, r.latent_stages);
  EXPECT_EQ(back.trial.init, "torch-default");
  EXPECT_TRUE(back.trial.freeze_decoder_too);
  EXPECT_EQ(back.trial.recycle_every, 250);
  EXPECT_EQ(back.trial.recycle_threshold, 0.05);
  EXPECT_EQ(back.trial.prune_by, "recon");
  EXPECT_EQ(back.trial.recycle_outgoing_scale, 0.3);
  EXPECT_TRUE(back.trial.recycle_decoder_too);
  EXPECT_EQ(back.trial.revive_at, 7);
  EXPECT_TRUE(back.trial.revive_fresh_decoder);
  EXPECT_TRUE(back.trial.freeze_active_readout);
  EXPECT_EQ(back.ball_spread, 0.25);
  EXPECT_EQ(back.ball_spread_to, 0.75);
  EXPECT_EQ(back.ball_spread_iters, 4000);
  EXPECT_EQ(back.scenes_file, "runs/x_scenes.csv");
  EXPECT_EQ(to_json(back), to_json(r));
}

// recipe.json as the trainer wrote it before the trial options moved into Recipe::trial
// (a 120-iteration trial run): it loads into the same knobs and is written back unchanged.
TEST(Recipe, LoadsAndRewritesAnEarlierRecipeFile) {
  const auto old = nlohmann::json::parse(R"({"ball_spread":0.0,"ball_spread_iters":60,
    "ball_spread_to":1.0,"batch":16,"beta":150.0,"beta_ramp":20,"capacity_iters":60,
    "capacity_max":12.0,"capacity_min":0.0,"dataset_size":1024,"freeze_active_readout":false,
    "freeze_convs_only":false,"freeze_decoder_too":true,"freeze_encoder_from":90,
    "freeze_encoder_to":110,"init":"kaiming","init_from":"","iterations":120,
    "latent_stages":[[0,2],[40,4],[80,3]],"lr":0.0005,"lr_decay_from":100,"lr_final":0.0001,
    "lr_warmup":10,"model":"beta-vae","out_init_scale":0.1,"prune_by":"recon",
    "recycle_decoder_too":true,"recycle_every":30,"recycle_outgoing_scale":0.3,
    "recycle_threshold":0.1,"reinit_after_warmup":true,"reinit_decoder":false,"revive_at":50,
    "revive_fresh_decoder":false,"seed":1,"vae_window_from":60,"vae_window_to":70,"warmup":20})");
  const Recipe r = recipe_from_json(old);
  EXPECT_EQ(r.iterations, 120);
  EXPECT_EQ(r.ball_spread_iters, 60);
  EXPECT_EQ(r.out_init_scale, 0.1);
  EXPECT_EQ(r.trial.warmup, 20);
  EXPECT_EQ(r.trial.lr_final, 0.0001);
  EXPECT_EQ(r.trial.prune_by, "recon");
  EXPECT_EQ(r.trial.revive_at, 50);
  EXPECT_EQ(r.trial.vae_window_to, 70);
  EXPECT_TRUE(r.trial.freeze_decoder_too);
  EXPECT_TRUE(r.trial.reinit_after_warmup);
  EXPECT_TRUE(r.scenes_file.empty());  // written before --scenes existed
  nlohmann::json rewritten = old;
  rewritten["scenes_file"] = "";
  EXPECT_EQ(to_json(r), rewritten);
}

// The first recipe.json files had only the keys read with j.at(): every later knob, trial or
// not, takes its default.
TEST(Recipe, LoadsTheFirstRecipeFormatWithDefaults) {
  const auto first = nlohmann::json::parse(R"({"model":"beta-vae","iterations":30000,"batch":64,
    "lr":0.0005,"beta":150.0,"capacity_max":12.0,"capacity_iters":15000,"dataset_size":50000,
    "seed":1})");
  EXPECT_EQ(to_json(recipe_from_json(first)), to_json(Recipe{}));
}

}  // namespace
}  // namespace curio::train
