#include "host_tools/experiment/run.hpp"

#include "host_tools/experiment/representations.hpp"

namespace curio::lab {

uint64_t world_seed(uint64_t run_seed) { return sim::world_seed_for_run(run_seed); }

const Representation* representation_of(const RunSpec& spec) {
  if (spec.algorithm.outcome != OutcomeSource::kLatents) return nullptr;
  return find_representation(spec.algorithm.representation);
}

Status make_explorer_config(const RunSpec& spec, ExplorerConfig* config) {
  ExplorerConfig c = spec.explorer;
  const Representation* rep = representation_of(spec);
  const Status s = configure_modules(spec.algorithm, c, rep ? rep->kl_order.data() : nullptr);
  if (s != Status::kOk) return s;
  *config = c;
  return validate(c);
}

std::string verdict_text(const RunResult& r) {
  std::string s;
  if (!r.module_latents.empty()) {
    for (int z : controllable_latents(r.verdicts, r.module_latents))
      s += (s.empty() ? "z" : ",z") + std::to_string(z);
  } else {
    for (size_t k = 0; k < r.verdicts.size(); ++k)
      if (r.verdicts[k].controllable) s += (s.empty() ? "" : ",") + r.module_names[k];
  }
  return s.empty() ? "none" : s;
}

std::string expected_verdict(const RunResult& r) {
  if (r.spec.algorithm.outcome == OutcomeSource::kEngineeredFeatures) return "ball";
  if (r.spec.algorithm.outcome == OutcomeSource::kLatents) {
    std::string s;
    for (int z : ball_latents(r.spec.algorithm.representation))
      s += (s.empty() ? "z" : ",z") + std::to_string(z);
    return s;
  }
  return "";
}

}  // namespace curio::lab
