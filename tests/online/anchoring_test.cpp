// Anchoring of curio-online (online_training.hpp): a training that opens latents keeps the
// already-open latents' code (their KL to the code before the training is penalised), so what is
// new in the images goes to the new latents; trainings that open nothing are not anchored; the
// option is refused without progressive latents and old runs resume with it off.
#include <cmath>

#include <gtest/gtest.h>
#include <torch/torch.h>

#include "host_tools/online/goal_space.hpp"
#include "host_tools/online/online_options.hpp"
#include "host_tools/online/online_training.hpp"
#include "tests/online/toy_training.hpp"

namespace curio::online {
namespace {

using toy::toy_images;

OnlineOptions toy_options(double anchor_weight) {
  OnlineOptions o = toy::toy_progressive_options(11);
  o.lr = 2e-3;
  o.anchor_weight = anchor_weight;
  return o;
}

// Mean |Δμ| of z0 and z1 over `images` across the second training (which opens z2, z3).
double old_latents_drift(double anchor_weight, TrainingStats* second, TrainingStats* third) {
  torch::set_num_threads(1);
  OnlineVae vae(toy_options(anchor_weight));
  vae.train(toy_images(24, false), 20, 0, {});  // C → 4: z0, z1 open
  const auto images = toy_images(48, true);
  const EncodedScenes before = encode_images(vae.model(), images);
  *second = vae.train(images, 20, 1, {});  // C → 8: z2, z3 open
  const EncodedScenes after = encode_images(vae.model(), images);
  *third = vae.train(images, 5, 2, {});   // opens nothing
  double drift = 0.0;
  for (size_t i = 0; i < before.mu.size(); ++i)
    if (i % 10 < 2) drift += std::abs(after.mu[i] - before.mu[i]);
  return drift / static_cast<double>(2 * images.size(0));
}

TEST(Anchoring, OpeningTrainingKeepsTheOldLatentsCode) {
  TrainingStats free_second, free_third, anchored_second, anchored_third;
  const double free_drift = old_latents_drift(0.0, &free_second, &free_third);
  const double anchored_drift = old_latents_drift(1000.0, &anchored_second, &anchored_third);
  EXPECT_EQ(free_second.anchored, 0);
  EXPECT_EQ(anchored_second.anchored, 2);
  EXPECT_GT(anchored_second.anchor_kl, 0.0);
  EXPECT_EQ(anchored_second.open_latents, 4);
  EXPECT_EQ(anchored_third.anchored, 0);  // nothing opened: the training is free
  EXPECT_GT(free_drift, 0.0);
  EXPECT_LT(anchored_drift, 0.5 * free_drift) << "anchored " << anchored_drift << " free " << free_drift;
}

TEST(Anchoring, OptionChecksAndOldRunsResumeWithItOff) {
  OnlineOptions o = toy_options(2.0);
  EXPECT_TRUE(check(o).empty());
  auto j = to_json(o);
  EXPECT_EQ(options_from_json(j).anchor_weight, 2.0);
  j.erase("anchor_weight");
  EXPECT_EQ(options_from_json(j).anchor_weight, 0.0);
  o.nats_per_latent = 0.0;  // all ten latents from the start: nothing opens later
  EXPECT_FALSE(check(o).empty());
  o.nats_per_latent = 3.0;
  o.anchor_weight = -1.0;
  EXPECT_FALSE(check(o).empty());
}

}  // namespace
}  // namespace curio::online
