#include "host_tools/experiment/algorithms.hpp"

#include "firmware/explore/module_layouts.hpp"

namespace curio::lab {

const std::vector<AlgorithmSpec>& known_algorithms() {
  static const std::vector<AlgorithmSpec> specs = [] {
    std::vector<AlgorithmSpec> v = {
        {"RPE", Algorithm::kRpe, OutcomeSource::kNone, 100, 1.0, "", 0,
         "random parameter exploration: θ ~ U[-1,1]^49 every episode"},
        {"RGE-EFR", Algorithm::kRge, OutcomeSource::kEngineeredFeatures, 100, 1.0, "", 0,
         "random goals in the 4-D engineered features (distractor x,y, ball x,y), one module"},
        {"MGE-EFR", Algorithm::kMge, OutcomeSource::kEngineeredFeatures, 100, 1.0, "", 0,
         "modular goals: distractor and ball modules chosen by learning progress"},
    };
    for (const auto& [rep, tag] : {std::pair{"beta_vae", "βVAE"}, std::pair{"vae", "VAE"}}) {
      const std::string t = tag;
      v.push_back({"RGE-" + t, Algorithm::kRge, OutcomeSource::kLatents, 400, 2.0, rep, 10,
                   "random goals in all 10 latents of the " + t + " (one module)"});
      v.push_back({"MGE-" + t, Algorithm::kMge, OutcomeSource::kLatents, 400, 2.0, rep, 2,
                   "modular goals: 5 modules of 2 latents of the " + t + ", grouped by KL"});
      v.push_back({"MGE-" + t + "-10", Algorithm::kMge, OutcomeSource::kLatents, 400, 2.0, rep, 1,
                   "modular goals: 10 single-latent modules of the " + t});
    }
    return v;
  }();
  return specs;
}

std::optional<AlgorithmSpec> find_algorithm(std::string_view name) {
  std::string n(name);
  for (const char* alias : {"bVAE", "betaVAE", "BVAE"}) {
    const auto pos = n.find(alias);
    if (pos != std::string::npos) n.replace(pos, std::string(alias).size(), "βVAE");
  }
  for (const auto& s : known_algorithms())
    if (s.name == n) return s;
  return std::nullopt;
}

Status configure_modules(const AlgorithmSpec& spec, ExplorerConfig& config,
                         const uint8_t* kl_order) {
  switch (spec.outcome) {
    case OutcomeSource::kNone:
    case OutcomeSource::kEngineeredFeatures:
      return set_efr_modules(config, spec.algorithm);
    case OutcomeSource::kLatents:
      if (kl_order == nullptr) return Status::kInvalidArgument;
      return set_latent_modules(config, kl_order, spec.group_size);
  }
  return Status::kInvalidArgument;
}

std::vector<std::string> module_names(const AlgorithmSpec& spec, const uint8_t* kl_order) {
  if (spec.algorithm == Algorithm::kRpe) return {};
  if (spec.outcome == OutcomeSource::kEngineeredFeatures) {
    if (spec.algorithm == Algorithm::kRge) return {"all"};
    return {"distractor", "ball"};
  }
  std::vector<std::string> names;
  for (int m = 0; m < kLatentDim / spec.group_size; ++m) {
    std::string name;
    for (int j = 0; j < spec.group_size; ++j) {
      const int latent = kl_order ? kl_order[m * spec.group_size + j] : m * spec.group_size + j;
      name += (j ? "+z" : "z") + std::to_string(latent);
    }
    names.push_back(spec.group_size == kLatentDim ? "all" : name);
  }
  return names;
}

}  // namespace curio::lab
