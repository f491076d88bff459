// Progressive latents of curio-online (online_training.hpp): the latent count follows C, held
// latents stay exactly at the prior through training and a checkpoint, opened groups become
// the goal modules, and old runs (no such option in options.json) resume with it off.
#include <array>
#include <cstdint>
#include <filesystem>

#include <gtest/gtest.h>
#include <torch/torch.h>

#include "host_tools/online/goal_space.hpp"
#include "host_tools/online/online_options.hpp"
#include "host_tools/online/online_training.hpp"
#include "tests/online/toy_training.hpp"

namespace curio::online {
namespace {

OnlineOptions toy_options() { return toy::toy_progressive_options(5); }
using toy::toy_images;

double max_abs_of_latent_weights(train::Vae& m, int l) {
  const double out = std::max(m->enc->fc_out->weight[l].abs().max().item<double>(),
                              m->enc->fc_out->weight[l + 10].abs().max().item<double>());
  return std::max(out, m->dec->fc1->weight.select(1, l).abs().max().item<double>());
}

TEST(ProgressiveLatents, OpenCountFollowsCapacityInGroups) {
  OnlineOptions o = toy_options();
  EXPECT_EQ(o.open_latents_at(0.0), 2);   // at least one group
  EXPECT_EQ(o.open_latents_at(6.0), 2);   // exactly one group's capacity: no second group
  EXPECT_EQ(o.open_latents_at(6.5), 4);
  EXPECT_EQ(o.open_latents_at(12.0), 4);
  EXPECT_EQ(o.open_latents_at(100.0), 10);
  o.group_size = 5;
  EXPECT_EQ(o.open_latents_at(12.0), 5);
  o.nats_per_latent = 0.0;
  EXPECT_FALSE(o.progressive());
  EXPECT_EQ(o.open_latents_at(1.0), 10);
}

TEST(ProgressiveLatents, HeldLatentsStayAtThePriorAndOpenedOnesTrain) {
  torch::set_num_threads(1);
  const OnlineOptions o = toy_options();
  OnlineVae vae(o);
  EXPECT_EQ(vae.open_latents(), 0);
  const auto images = toy_images(24);
  // First training ends at C = 12 · 20/60 = 4 nats: one group (2 latents).
  const TrainingStats a = vae.train(images, 20, 0, {});
  EXPECT_EQ(a.open_latents, 2);
  for (int l = 0; l < 2; ++l) EXPECT_GT(max_abs_of_latent_weights(vae.model(), l), 0.0) << "z" << l;
  for (int l = 2; l < 10; ++l) EXPECT_EQ(max_abs_of_latent_weights(vae.model(), l), 0.0) << "z" << l;
  const EncodedScenes e = encode_images(vae.model(), images);
  for (int l = 2; l < 10; ++l) EXPECT_EQ(e.kl[static_cast<size_t>(l)], 0.0) << "z" << l;

  // Second training ends at C = 8: a second group opens, the rest stay held; a checkpoint
  // round trip keeps which latents are held.
  const TrainingStats b = vae.train(images, 20, 1, {});
  EXPECT_EQ(b.open_latents, 4);
  for (int l = 2; l < 4; ++l) EXPECT_GT(max_abs_of_latent_weights(vae.model(), l), 0.0) << "z" << l;
  for (int l = 4; l < 10; ++l) EXPECT_EQ(max_abs_of_latent_weights(vae.model(), l), 0.0) << "z" << l;
  const auto path = std::filesystem::temp_directory_path() / "curio_progressive_latents_test.pt";
  vae.save(path.string(), images.size(0));
  OnlineVae back(o);
  back.load(path.string());
  EXPECT_EQ(back.open_latents(), 4);
  std::filesystem::remove(path);
}

TEST(ProgressiveLatents, ANonProgressiveRunTrainsAllTen) {
  torch::set_num_threads(1);
  OnlineOptions o = toy_options();
  o.nats_per_latent = 0.0;
  OnlineVae vae(o);
  EXPECT_EQ(vae.open_latents(), 10);
  EXPECT_EQ(vae.train(toy_images(16), 5, 0, {}).open_latents, 10);
}

TEST(ProgressiveLatents, GroupOrderKeepsGroupsTogether) {
  // z1 alone has the largest KL, but the group {z2, z3} has the larger sum.
  const std::array<double, 10> kl{0.1, 3.0, 2.0, 1.9, 0, 0, 0, 0, 0, 0};
  const auto order = group_order(kl, 2);
  const std::array<uint8_t, 10> want{2, 3, 1, 0, 4, 5, 6, 7, 8, 9};
  EXPECT_EQ(order, want);
  const std::array<double, 10> flat{};
  const std::array<uint8_t, 10> identity{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  EXPECT_EQ(group_order(flat, 5), identity);
  EXPECT_THROW(group_order(kl, 3), std::runtime_error);
}

TEST(ProgressiveLatents, OptionsWrittenBeforeItResumeWithItOff) {
  OnlineOptions o = toy_options();
  auto j = to_json(o);
  EXPECT_EQ(options_from_json(j).nats_per_latent, 3.0);
  j.erase("nats_per_latent");
  j.erase("release_scale");
  const OnlineOptions old = options_from_json(j);
  EXPECT_FALSE(old.progressive());
  EXPECT_EQ(old.release_scale, 0.3);
  o.nats_per_latent = -1.0;
  EXPECT_FALSE(check(o).empty());
}

}  // namespace
}  // namespace curio::online
