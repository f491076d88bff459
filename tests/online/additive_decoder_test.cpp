// Additive decoding (DecoderImpl::additive_group_size, curio-online --decoder additive): each
// open latent group changes the image by what it alone decodes to, so the cross-difference
// of two groups' codes is zero (a group cannot refine what another holds), one open group
// decodes exactly as SPEC §3's decoder, held groups add nothing, and old runs resume with it off.
#include <gtest/gtest.h>
#include <torch/torch.h>

#include "host_tools/online/online_options.hpp"
#include "host_tools/online/online_training.hpp"
#include "host_tools/vae/vae_model.hpp"

namespace curio::online {
namespace {

// A seeded model with z0..z(open − 1) open (the rest held) and a 2-latent-group additive
// decoder when asked.
train::Vae model_with_open_latents(size_t open, bool additive, uint64_t seed) {
  torch::manual_seed(seed);
  train::Vae m;
  m->kaiming_init(1.0);
  train::LatentMask held{};
  for (size_t l = open; l < 10; ++l) held[l] = true;
  m->hold_latents(held);
  m->dec->additive_group_size = additive ? 2 : 0;
  return m;
}

// max |f(a0, a1) + f(b0, b1) − f(a0, b1) − f(b0, a1)| over the pixels, where x0 is the value of
// group (z0, z1) and x1 of group (z2, z3): zero for a decoder additive in the two groups.
double cross_difference(train::Vae& m) {
  torch::NoGradGuard no_grad;
  torch::manual_seed(4);
  const auto a = torch::randn({1, 10}), b = torch::randn({1, 10});
  auto mix = [&](const torch::Tensor& first, const torch::Tensor& second) {
    auto z = second.clone();
    z.narrow(1, 0, 2).copy_(first.narrow(1, 0, 2));
    return m->dec->forward(z);
  };
  return (mix(a, a) + mix(b, b) - mix(a, b) - mix(b, a)).abs().max().item<double>();
}

TEST(AdditiveDecoder, GroupsAddTheirOwnChangesOnly) {
  train::Vae additive = model_with_open_latents(4, true, 3);
  train::Vae shared = model_with_open_latents(4, false, 3);
  EXPECT_LT(cross_difference(additive), 1e-3);
  EXPECT_GT(cross_difference(shared), 1e-2) << "SPEC §3's decoder mixes the groups";
  // It is D(0) + Σ_g [D(z ⊙ m_g) − D(0)] of the plain network, over the open groups only.
  torch::NoGradGuard no_grad;
  const auto z = torch::randn({3, 10});
  const auto zero = torch::zeros({1, 10});
  auto first = z.clone(), second = z.clone();
  first.narrow(1, 2, 8).zero_();
  second.narrow(1, 0, 2).zero_();
  second.narrow(1, 4, 6).zero_();
  const auto d0 = additive->dec->decode(zero);
  const auto expected = additive->dec->decode(first) + additive->dec->decode(second) - d0;
  EXPECT_LT((additive->dec->forward(z) - expected).abs().max().item<double>(), 1e-4);
}

TEST(AdditiveDecoder, OneOpenGroupDecodesExactlyAsTheSpecDecoder) {
  torch::set_num_threads(1);  // bit-exactness is per thread count, as for every online run
  train::Vae m = model_with_open_latents(2, false, 5);
  torch::NoGradGuard no_grad;
  const auto z = torch::randn({4, 10});
  const auto plain = m->dec->forward(z);
  m->dec->additive_group_size = 2;
  EXPECT_TRUE(torch::equal(m->dec->forward(z), plain));
}

TEST(AdditiveDecoder, OptionSetsTheModelsDecoderAndOldRunsResumeWithSpec) {
  OnlineOptions o;
  o.decoder = "additive";
  EXPECT_TRUE(check(o).empty());
  EXPECT_EQ(OnlineVae(o).model()->dec->additive_group_size, o.group_size);
  o.decoder = "spec";
  EXPECT_EQ(OnlineVae(o).model()->dec->additive_group_size, 0);
  auto j = to_json(o);
  j.erase("decoder");
  EXPECT_EQ(options_from_json(j).decoder, "spec");
  o.decoder = "sum";
  EXPECT_FALSE(check(o).empty());
}

}  // namespace
}  // namespace curio::online
