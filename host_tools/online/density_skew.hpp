// Density-skewed training batches for an online run (OnlineOptions::skew_alpha): the idea of
// Skew-Fit (Pong et al., ICML 2020), with a k-nearest-neighbour density in the goal modules'
// own spaces instead of the VAE's likelihood.
//
// Why: the agent's images are far from uniform over what it can reach (the ball rests in most
// of them, and where it moved, it moved near where it moved before). A β-VAE trained on them
// spends its prior on the common scenes and folds the rare ones in between (session 14: the
// ball's code is a spiral), so goals drawn from the prior (SPEC §2.3) miss most of the reached
// arena. Training on images drawn with probability ∝ p̂(code)^α, α < 0, flattens the data the
// code is learned from toward uniform over the reached scenes, as a passive β-VAE's uniform
// scenes are; the goals stay SPEC's prior goals.
//
// The density: for each open module (a group of latents, its μ under the model before the
// training), r_g(i) = distance from image i's code to its k-th nearest other image's code;
// p̂_g(i) ∝ r_g(i)^(−d_g); p̂(i) = Π_g p̂_g(i) (modules taken as independent, as the modules
// are meant to be). So the weight is w(i) = Π_g r_g(i)^(−α·d_g), normalised to mean 1 and
// capped at `cap` (the few isolated images must not become the whole batch). A module whose
// codes are all equal (held latents, μ = 0) carries no density and is skipped. Images and the
// model's own code only: no positions, objects or counts.
#pragma once
#include <cstdint>
#include <vector>

namespace curio::online {

// codes: n × stride floats, image i's latent l at codes[i * stride + l]. modules: the latent
// indices of each module. Returns n weights with mean 1 (all 1 when no module has spread or
// n ≤ k; empty when n ≤ 0). O(n² · Σ d_g) time, O(n) memory per module.
std::vector<double> density_skew_weights(const std::vector<float>& codes, int stride, int n,
                                         const std::vector<std::vector<int>>& modules, int k,
                                         double alpha, double cap);

// Draws an index with probability ∝ weights, from u uniform in (0, 1): `cumulative` holds the
// running sums of the weights (cumulative_weights).
std::vector<double> cumulative_weights(const std::vector<double>& weights);
uint32_t draw_weighted(const std::vector<double>& cumulative, double u);

}  // namespace curio::online
