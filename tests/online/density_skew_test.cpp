// Density-skewed batches (density_skew.hpp): weights grow where codes are sparse, flatten the
// data toward uniform over what was reached, are capped, skip modules without spread, and a
// training with them is deterministic; old runs resume with them off.
#include "host_tools/online/density_skew.hpp"

#include <gtest/gtest.h>
#include <torch/torch.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "host_tools/online/online_options.hpp"
#include "host_tools/online/online_training.hpp"
#include "tests/online/toy_training.hpp"

namespace curio::online {
namespace {

// 90 codes in a tight cluster (the ball at rest) and 10 on a circle of radius 2 (moved), in
// latents 2 and 3 of 4; latents 0 and 1 are all zero (held).
std::vector<float> rest_heavy_codes() {
  std::vector<float> c(100 * 4, 0.0f);
  for (int i = 0; i < 100; ++i) {
    const double a = 0.7 * i;
    const double r = i < 90 ? 0.01 * (1 + i % 7) : 2.0;
    c[static_cast<size_t>(i) * 4 + 2] = static_cast<float>(r * std::cos(a));
    c[static_cast<size_t>(i) * 4 + 3] = static_cast<float>(r * std::sin(a));
  }
  return c;
}

double share_of_last_ten(const std::vector<double>& w) {
  return std::accumulate(w.begin() + 90, w.end(), 0.0) / std::accumulate(w.begin(), w.end(), 0.0);
}

TEST(DensitySkew, SparseCodesGainWeightAndAlphaZeroIsUniform) {
  const auto codes = rest_heavy_codes();
  const std::vector<std::vector<int>> modules = {{2, 3}};
  const auto flat = density_skew_weights(codes, 4, 100, modules, 5, 0.0, 20.0);
  for (double x : flat) EXPECT_DOUBLE_EQ(x, 1.0);
  const auto half = density_skew_weights(codes, 4, 100, modules, 5, -0.5, 1000.0);
  const auto full = density_skew_weights(codes, 4, 100, modules, 5, -1.0, 1000.0);
  EXPECT_GT(share_of_last_ten(half), 0.5) << "10 % of the images, sparse: most of the weight";
  EXPECT_GT(share_of_last_ten(full), share_of_last_ten(half));
  EXPECT_NEAR(std::accumulate(full.begin(), full.end(), 0.0) / 100, 1.0, 1e-9);
}

TEST(DensitySkew, CapBoundsEveryWeightAndModulesWithoutSpreadAreSkipped) {
  const auto codes = rest_heavy_codes();
  const auto capped = density_skew_weights(codes, 4, 100, {{2, 3}}, 5, -1.0, 3.0);
  EXPECT_LE(*std::max_element(capped.begin(), capped.end()), 3.0 + 1e-9);
  EXPECT_LT(share_of_last_ten(capped), 0.31);
  // Latents 0 and 1 are zero on every image: no density, so no skew.
  const auto held = density_skew_weights(codes, 4, 100, {{0, 1}}, 5, -1.0, 20.0);
  for (double x : held) EXPECT_DOUBLE_EQ(x, 1.0);
  // Fewer images than neighbours: uniform.
  for (double x : density_skew_weights(codes, 4, 5, {{2, 3}}, 5, -1.0, 20.0)) EXPECT_DOUBLE_EQ(x, 1.0);
}

TEST(DensitySkew, WeightedDrawsFollowTheWeights) {
  const auto cum = cumulative_weights({1.0, 0.0, 3.0});
  int count[3] = {};
  for (int i = 0; i < 4000; ++i) ++count[draw_weighted(cum, (i + 0.5) / 4000)];
  EXPECT_EQ(count[0], 1000);
  EXPECT_EQ(count[1], 0);
  EXPECT_EQ(count[2], 3000);
  EXPECT_EQ(draw_weighted(cum, 1.0), 2u);
}

// A second training with the skew reports its effective sample size and repeats bit for bit.
TEST(DensitySkew, SkewedTrainingIsDeterministicAndReportsItsSampleSize) {
  torch::set_num_threads(1);
  OnlineOptions o = toy::toy_progressive_options(3);
  o.skew_alpha = -1.0;
  o.skew_neighbours = 3;
  const torch::Tensor images = toy::toy_images(24, /*ball_moves=*/true);
  auto run = [&] {
    OnlineVae vae(o);
    const TrainingStats first = vae.train(images, 30, 0, {});
    EXPECT_EQ(first.skew_ess, 0.0) << "the first training has no code to skew by";
    const TrainingStats second = vae.train(images, 30, 1, {});
    EXPECT_GT(second.skew_ess, 0.0);
    EXPECT_LE(second.skew_ess, 1.0);
    return vae.model()->parameters()[0].clone();
  };
  EXPECT_TRUE(torch::equal(run(), run()));
}

TEST(DensitySkew, OptionChecksAndOldRunsResumeWithItOff) {
  OnlineOptions o;
  o.skew_alpha = -1.0;
  EXPECT_TRUE(check(o).empty());
  auto j = to_json(o);
  EXPECT_EQ(options_from_json(j).skew_alpha, -1.0);
  j.erase("skew_alpha");
  j.erase("skew_neighbours");
  j.erase("skew_cap");
  EXPECT_EQ(options_from_json(j).skew_alpha, 0.0);
  o.skew_alpha = 0.5;
  EXPECT_FALSE(check(o).empty());
  o.skew_alpha = -1.0;
  o.skew_cap = 0.5;
  EXPECT_FALSE(check(o).empty());
  o.skew_cap = 20.0;
  o.skew_neighbours = 0;
  EXPECT_FALSE(check(o).empty());
}

}  // namespace
}  // namespace curio::online
