// The capacity term of curio-online's objective (online_training.hpp): "abs" holds the KL at C
// (it pulls the KL up when the code needs fewer nats), "hinge" only caps it, and a kl_weight
// price per nat keeps a hinge-trained code below C; old runs resume with the recipe's "abs".
#include <gtest/gtest.h>
#include <torch/torch.h>

#include "host_tools/online/online_options.hpp"
#include "host_tools/online/online_training.hpp"
#include "tests/online/toy_training.hpp"

namespace curio::online {
namespace {

// A toy training whose C reaches 12 nats within 10 iterations, so the last 100 iterations (the
// window of TrainingStats::kl) all run at C = 12: more than these 24 scenes of a distractor on
// one diagonal need at a price of 20 nats of BCE per nat.
TrainingStats train_toy(const std::string& penalty, double kl_weight) {
  torch::set_num_threads(1);
  OnlineOptions o = toy::toy_progressive_options(5);
  o.nats_per_latent = 0.0;  // all ten latents: the objective alone decides what they carry
  o.capacity_iters = 10;
  o.lr = 2e-3;
  o.kl_penalty = penalty;
  o.kl_weight = kl_weight;
  OnlineVae vae(o);
  return vae.train(toy::toy_images(24), 150, 0, {});
}

TEST(KlPenalty, AbsHoldsTheKlAtCapacityAndTheHingeWithAPriceStaysBelow) {
  const TrainingStats held = train_toy("abs", 0.0);
  const TrainingStats capped = train_toy("hinge", 20.0);
  EXPECT_DOUBLE_EQ(held.capacity, 12.0);
  EXPECT_NEAR(held.kl, 12.0, 1.0) << "abs pulls the KL up to C";
  EXPECT_LT(capped.kl, 0.5 * capped.capacity) << "the hinge does not pull; the price pushes down";
  EXPECT_LT(capped.kl, held.kl);
}

TEST(KlPenalty, OptionChecksAndOldRunsResumeWithTheRecipesTerm) {
  OnlineOptions o;
  o.kl_penalty = "hinge";
  o.kl_weight = 2.0;
  EXPECT_TRUE(check(o).empty());
  auto j = to_json(o);
  EXPECT_EQ(options_from_json(j).kl_penalty, "hinge");
  EXPECT_EQ(options_from_json(j).kl_weight, 2.0);
  j.erase("kl_penalty");
  j.erase("kl_weight");
  EXPECT_EQ(options_from_json(j).kl_penalty, "abs");
  EXPECT_EQ(options_from_json(j).kl_weight, 0.0);
  o.kl_penalty = "square";
  EXPECT_FALSE(check(o).empty());
  o.kl_penalty = "abs";
  o.kl_weight = -1.0;
  EXPECT_FALSE(check(o).empty());
}

}  // namespace
}  // namespace curio::online
