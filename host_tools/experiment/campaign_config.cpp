#include "host_tools/experiment/campaign_config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "host_tools/cli/seed_text.hpp"
#include "host_tools/experiment/explore_strategies.hpp"
#include "host_tools/experiment/representations.hpp"

namespace curio::lab {

std::optional<CompetenceMeasure> parse_competence_measure(const std::string& text) {
  for (const auto m : {CompetenceMeasure::kClipped, CompetenceMeasure::kScaled})
    if (text == to_string(m)) return m;
  return std::nullopt;
}

std::optional<TieRule> parse_tie_rule(const std::string& text) {
  if (text == "earliest") return TieRule::kEarliest;
  if (text == "latest") return TieRule::kLatest;
  return std::nullopt;
}

std::optional<std::vector<uint64_t>> parse_seeds(const std::string& text, std::string* error,
                                                 size_t max_seeds) {
  std::vector<uint64_t> seeds;
  uint64_t count = 0;  // seeds the list names, counted before they are stored
  size_t pos = 0;
  auto parse_int = [&](const std::string& s, uint64_t* out) {
    const auto seed = cli::parse_seed(s);
    if (seed) *out = *seed;
    return seed.has_value();
  };
  while (pos <= text.size()) {
    const size_t comma = text.find(',', pos);
    const std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    const size_t dash = item.find('-');
    uint64_t a = 0, b = 0;
    if (dash == std::string::npos) {
      if (!parse_int(item, &a)) {
        *error = "bad seed '" + item + "' in '" + text +
                 "' (use e.g. 0-14 or 0,3,7; a seed is a whole number 0 to 2^64 - 1)";
        return std::nullopt;
      }
      b = a;
    } else if (!parse_int(item.substr(0, dash), &a) || !parse_int(item.substr(dash + 1), &b) || b < a) {
      *error = "bad seed range '" + item + "' in '" + text + "' (use FIRST-LAST with FIRST ≤ LAST)";
      return std::nullopt;
    }
    // b - a + 1 overflows only for 0-(2^64 - 1), which is over any max_seeds anyway.
    count += (b - a >= max_seeds) ? max_seeds + 1 : b - a + 1;
    if (count > max_seeds) {
      RunSpec typical;  // 400 + 10,000 episodes
      typical.explorer.n_bootstrap = 400;
      const double gb = double(count) * double(held_bytes_per_run(typical)) / 1e9;
      char held[96];
      std::snprintf(held, sizeof held, "; %.1f KB of each run is kept for the summary: %.1f GB",
                    held_bytes_per_run(typical) / 1e3, gb);
      *error = "seed list '" + text.substr(0, 64) + (text.size() > 64 ? "…" : "") + "' names " +
               (comma == std::string::npos ? "" : "at least ") + std::to_string(count) +
               " seeds; a campaign has at most " + std::to_string(max_seeds) + " runs (" +
               std::to_string(count) + " runs would not fit in memory" + held + ")";
      return std::nullopt;
    }
    for (uint64_t s = a;; ++s) {  // a <= b, and b may be 2^64 - 1: stop at b, not after it
      seeds.push_back(s);
      if (s == b) break;
    }
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  std::set<uint64_t> unique(seeds.begin(), seeds.end());
  if (unique.size() != seeds.size()) {
    *error = "seed list '" + text + "' repeats a seed";
    return std::nullopt;
  }
  return seeds;
}

std::vector<RunSpec> expand_runs(const CampaignConfig& c) {
  std::vector<RunSpec> runs;
  for (double sigma : c.sigmas) {
    for (const auto& name : c.algorithms) {
      const auto algo = find_algorithm(name);
      if (!algo) continue;
      for (const uint64_t seed : c.seeds) {
        RunSpec r;
        r.algorithm = *algo;
        r.physics = c.physics;
        r.world = c.world;
        ExplorerConfig& e = r.explorer;
        e.seed = seed;
        e.sigma = static_cast<float>(sigma);
        e.n_bootstrap = c.bootstrap >= 0 ? c.bootstrap : algo->default_bootstrap;
        e.n_episodes = c.episodes;
        e.competence_cap = static_cast<float>(
            c.competence_clip > 0 ? c.competence_clip : algo->default_competence_clip);
        e.window = static_cast<float>(c.window);
        e.epsilon = static_cast<float>(c.epsilon);
        e.tie_rule = c.tie_rule;
        e.competence_measure = c.competence_measure;
        if (const auto s = find_explore_strategy(c.explore)) apply_explore_strategy(*s, &e);
        runs.push_back(r);
      }
    }
  }
  return runs;
}

size_t held_bytes_per_run(const RunSpec& spec) {
  const size_t episodes = static_cast<size_t>(std::max(spec.explorer.n_bootstrap, 0)) +
                          static_cast<size_t>(std::max(spec.explorer.n_episodes, 0));
  const size_t checkpoints = 31 + episodes / 100 + 1;            // curve_checkpoints
  const size_t samples = episodes / static_cast<size_t>(std::max(spec.interest_every, 1)) + 1;
  const size_t modules = 10;                                      // the most any algorithm has
  // ratio (8) + checkpoint (4) + grasps (4) per checkpoint; a row of interest per sample
  // (vector header 24 + 4 per module) and its episode (4); spec, names, verdicts.
  return 16 * checkpoints + samples * (28 + 4 * modules) + modules * 96 + 2048;
}

size_t record_bytes_per_run(const RunSpec& spec) {
  const size_t episodes = static_cast<size_t>(std::max(spec.explorer.n_bootstrap, 0)) +
                          static_cast<size_t>(std::max(spec.explorer.n_episodes, 0));
  return 2 * 9 * episodes + held_bytes_per_run(spec);  // x and y, ≤ 9 bytes each in CBOR
}

std::vector<std::string> validate_campaign(const CampaignConfig& c) {
  std::vector<std::string> problems;
  // Refused before the runs are expanded: the count alone decides.
  const uint64_t n_runs = static_cast<uint64_t>(c.algorithms.size()) * c.seeds.size() * c.sigmas.size();
  if (n_runs > kMaxCampaignRuns) {
    RunSpec typical;
    typical.explorer.n_bootstrap = std::max(c.bootstrap, 400);
    typical.explorer.n_episodes = std::max(c.episodes, 0);
    const double gb = double(n_runs) * double(held_bytes_per_run(typical)) / 1e9;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f GB", gb);
    problems.push_back("the campaign has " + std::to_string(n_runs) + " runs (" +
                       std::to_string(c.algorithms.size()) + " algorithms × " +
                       std::to_string(c.seeds.size()) + " seeds × " +
                       std::to_string(c.sigmas.size()) + " σ); curio-lab runs at most " +
                       std::to_string(kMaxCampaignRuns) + " in one campaign (this one would " +
                       "hold about " + buf + " for its summary): split it into campaigns");
    return problems;
  }
  if (c.algorithms.empty()) problems.push_back("no algorithm given (--algos)");
  for (const auto& name : c.algorithms) {
    if (!find_algorithm(name)) {
      std::string known;
      for (const auto& s : known_algorithms()) known += (known.empty() ? "" : ", ") + s.name;
      problems.push_back("--algos: unknown algorithm '" + name + "' (known: " + known + ")");
    }
  }
  if (!find_explore_strategy(c.explore))
    problems.push_back("--explore: unknown strategy '" + c.explore + "' (known: " +
                       explore_strategy_names() + ")");
  if (c.seeds.empty()) problems.push_back("no seed given (--seeds)");
  if (c.sigmas.empty()) problems.push_back("no σ given (--noise)");
  for (double s : c.sigmas)
    if (!(s >= 0.0) || !std::isfinite(s)) {
      char got[32];
      std::snprintf(got, sizeof got, "%g", s);
      problems.push_back(std::string("--noise: σ must be a finite number ≥ 0 (got ") + got + ")");
    }
  if (c.episodes <= 0) problems.push_back("--episodes must be > 0");
  else if (c.episodes % 5 != 0)
    problems.push_back("--episodes must be a multiple of 5 (4 explore + 1 exploit per step)");
  if (c.bootstrap < -1) problems.push_back("--bootstrap must be ≥ 0");
  if (!((c.competence_clip > 0.0 && std::isfinite(c.competence_clip)) || c.competence_clip == -1.0))
    problems.push_back("--competence-clip (D) must be > 0");
  if (!(c.window >= 1.0) || !std::isfinite(c.window)) problems.push_back("--window (W) must be a finite number ≥ 1");
  if (!(c.epsilon >= 0.0 && c.epsilon <= 1.0)) problems.push_back("--epsilon must be in [0, 1]");
  if (!(c.world.grasp_radius >= 0.0) || !std::isfinite(c.world.grasp_radius)) problems.push_back("--grasp-radius must be a finite number ≥ 0");
  if (!(c.world.distractor_noise >= 0.0) || !std::isfinite(c.world.distractor_noise)) problems.push_back("--distractor-noise must be a finite number ≥ 0");
  if (c.threads < 0) problems.push_back("--threads must be ≥ 0");
  for (const auto& name : c.algorithms) {
    const auto algo = find_algorithm(name);
    if (algo && algo->outcome == OutcomeSource::kLatents &&
        !find_representation(algo->representation))
      problems.push_back(name + " needs the " + algo->representation +
                         " weights (firmware/nn/models/" + algo->representation +
                         "_weights.hpp), which this build does not have: train and quantize "
                         "them (docs/training.md), then rebuild");
  }
  if (!problems.empty()) return problems;
  // The firmware's own validation catches everything else (capacity above all).
  for (const auto& run : expand_runs(c)) {
    ExplorerConfig config;
    const Status s = make_explorer_config(run, &config);
    if (s == Status::kCapacityTooSmall) {
      problems.push_back("archive capacity " + std::to_string(kArchiveCapacity) +
                         " is too small for " + std::to_string(run.explorer.n_bootstrap) +
                         " bootstrap + " + std::to_string(run.explorer.n_episodes) +
                         " episodes (rebuild with -DCURIO_ARCHIVE_CAPACITY=N)");
      break;
    }
    if (s != Status::kOk) {
      problems.push_back("the explorer rejects the configuration of " + run.algorithm.name + ": " +
                         to_string(s));
      break;
    }
  }
  return problems;
}

}  // namespace curio::lab
