// Disentanglement estimators for the factor report: Pearson correlation of each latent
// mean with each ground-truth factor, and the Mutual Information Gap (Chen et al. 2018)
// on discretised values. Plain C++ (no LibTorch) so they are testable on synthetic data.
#pragma once
#include <span>
#include <vector>

namespace curio::train {

// Pearson correlation; 0 when either input is constant (no linear relation measurable).
double pearson(std::span<const double> a, std::span<const double> b);

// Equal-width bins over [lo, hi] (values outside are clamped into the end bins).
std::vector<int> discretize(std::span<const double> v, int bins, double lo, double hi);
// Equal-width bins over the sample's own [min, max] (all 0 when constant).
std::vector<int> discretize_to_range(std::span<const double> v, int bins);

// Plug-in (histogram) estimates in nats. Labels must lie in [0, bins).
double entropy(std::span<const int> labels, int bins);
double mutual_information(std::span<const int> a, int bins_a, std::span<const int> b, int bins_b);

struct MigOptions {
  int bins = 20;             // for latents and factors alike
  double factor_lo = -1.0;   // factors are positions uniform in [-1, 1]
  double factor_hi = 1.0;
};

struct MigResult {
  // normalized_mi[latent][factor] = I(latent; factor) / H(factor).
  std::vector<std::vector<double>> normalized_mi;
  std::vector<double> gap_per_factor;  // (top − second) normalized MI per factor
  double mig = 0.0;                    // mean of gap_per_factor
};

// latents[l][i], factors[k][i]: column per variable, one row per sample. Each latent is
// discretised over its own range, each factor over [factor_lo, factor_hi].
MigResult mutual_information_gap(const std::vector<std::vector<double>>& latents,
                                 const std::vector<std::vector<double>>& factors,
                                 const MigOptions& options = {});

}  // namespace curio::train
