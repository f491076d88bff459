// SPEC §4's reference results (σ = 0.05, 15 seeds; 20 for RPE): mean ± std of the
// exploration ratio at N = 1000, 3000, 5000 and 9666 episodes.
#pragma once
#include <optional>
#include <string_view>

namespace curio::lab {

struct ReferenceRow {
  std::string_view algorithm;
  double mean[4];
  double std[4];
};

inline constexpr int kReferenceEpisodes[4] = {1000, 3000, 5000, 9666};

inline constexpr ReferenceRow kReferenceResults[] = {
    {"MGE-EFR", {.184, .445, .576, .693}, {.051, .088, .089, .083}},
    {"MGE-βVAE", {.118, .403, .555, .670}, {.050, .081, .079, .071}},
    {"RGE-βVAE", {.092, .263, .354, .482}, {.018, .050, .059, .056}},
    {"RGE-VAE", {.089, .226, .311, .426}, {.023, .047, .046, .052}},
    {"RGE-EFR", {.097, .230, .312, .426}, {.040, .083, .096, .096}},
    {"MGE-VAE", {.072, .203, .265, .344}, {.021, .040, .052, .064}},
    {"RPE", {.024, .061, .097, .163}, {.004, .005, .006, .008}},
};

inline std::optional<ReferenceRow> reference_for(std::string_view algorithm) {
  for (const auto& r : kReferenceResults)
    if (r.algorithm == algorithm) return r;
  return std::nullopt;
}

}  // namespace curio::lab
