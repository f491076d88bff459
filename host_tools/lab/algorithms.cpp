#include "host_tools/lab/algorithms.hpp"

#include "explore/module_layouts.hpp"

namespace curio::lab {

const std::vector<AlgorithmSpec>& known_algorithms() {
  static const std::vector<AlgorithmSpec> specs = {
      {"RPE", Algorithm::kRpe, OutcomeSource::kNone, 100,
       "random parameter exploration: θ ~ U[-1,1]^49 every episode"},
      {"RGE-EFR", Algorithm::kRge, OutcomeSource::kEngineeredFeatures, 100,
       "random goals in the 4-D engineered features (distractor x,y, ball x,y), one module"},
      {"MGE-EFR", Algorithm::kMge, OutcomeSource::kEngineeredFeatures, 100,
       "modular goals: distractor and ball modules chosen by learning progress"},
  };
  return specs;
}

std::optional<AlgorithmSpec> find_algorithm(std::string_view name) {
  for (const auto& s : known_algorithms())
    if (s.name == name) return s;
  return std::nullopt;
}

Status configure_modules(const AlgorithmSpec& spec, ExplorerConfig& config) {
  switch (spec.outcome) {
    case OutcomeSource::kNone:
    case OutcomeSource::kEngineeredFeatures:
      return set_efr_modules(config, spec.algorithm);
  }
  return Status::kInvalidArgument;
}

std::vector<std::string> module_names(const AlgorithmSpec& spec) {
  if (spec.algorithm == Algorithm::kRpe) return {};
  if (spec.algorithm == Algorithm::kRge) return {"all"};
  return {"distractor", "ball"};
}

}  // namespace curio::lab
