// A campaign's configuration: algorithms × seeds × σ values and everything else that decides
// its results; its parsing, validation and expansion into runs. Shared by curio-lab (which runs
// campaigns: host_tools/lab/campaign_runner.hpp) and curio-controller (a campaign of one run,
// so that both write the same result files: report.hpp).
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "host_tools/experiment/run.hpp"

namespace curio::lab {

struct CampaignConfig {
  std::vector<std::string> algorithms = {"RPE", "RGE-EFR", "MGE-EFR"};
  std::vector<uint64_t> seeds = {0, 1, 2};  // each 0 to 2^64 - 1 (host_tools/cli/seed_text.hpp)
  std::vector<double> sigmas = {0.05};
  sim::Physics physics = sim::Physics::kKinematic;
  sim::WorldParams world;
  int episodes = 10000;
  int bootstrap = -1;              // < 0: each algorithm's default (SPEC §2.2)
  double competence_clip = -1.0;   // D; < 0: each algorithm's default (EFR 1, learned 2)
  double window = 1000.0;
  double epsilon = 0.1;
  // 1-NN ties (SPEC §2.2; firmware/explore/nearest_neighbour.hpp says why)
  TieRule tie_rule = TieRule::kLatest;
  CompetenceMeasure competence_measure = CompetenceMeasure::kClipped;  // how D enters (§2.5)
  // The goal-exploration strategy of every goal run (explore_strategies.hpp): "spec" is §2.
  std::string explore = "spec";
  int threads = 0;                 // 0: all cores
  std::string out_dir = "out/lab";
  bool quiet = false;
  // Also write runs/<run>_scenes.csv (host_tools/lab/scene_log.hpp).
  bool save_scenes = false;
  // Print each run's archive checksum (firmware/explore/fnv1a.hpp) as it finishes.
  bool print_checksum = false;
};

// The most runs (algorithms × seeds × σ values) one campaign may have: curio-lab keeps a few
// KB of every run for the summary (held_bytes_per_run) and its record on disk until the report
// is written (record_bytes_per_run); 100,000 runs hold at most 2 GB. Larger campaigns are refused
// before any work, with the memory they would take.
inline constexpr size_t kMaxCampaignRuns = 100000;

// "0-14", "0,3,7", "1-3,8" → seeds, each read by cli::parse_seed (0 to 2^64 - 1, digits
// only). nullopt with *error on bad syntax, or when the list has more than `max_seeds` seeds
// (counted before any is stored: "0-99999999" is refused at once).
std::optional<std::vector<uint64_t>> parse_seeds(const std::string& text, std::string* error,
                                                 size_t max_seeds = kMaxCampaignRuns);

// "clip" or "scale" (the names to_string gives) → the measure; nullopt for anything else.
std::optional<CompetenceMeasure> parse_competence_measure(const std::string& text);
// "earliest" or "latest" (the --tie-rule option of curio-lab and curio-controller).
std::optional<TieRule> parse_tie_rule(const std::string& text);

// Every problem with the configuration, checked before any work starts (empty: valid).
std::vector<std::string> validate_campaign(const CampaignConfig& config);

// The runs of the campaign, in a fixed order (σ, algorithm, seed).
std::vector<RunSpec> expand_runs(const CampaignConfig& config);

// Upper estimates, in bytes, of what curio-lab keeps of one finished run of `spec`: in memory
// for the summary (its checkpoints, interest samples, verdicts), and on disk as its record
// (host_tools/lab/run_record.hpp: every episode's final ball position besides).
size_t held_bytes_per_run(const RunSpec& spec);
size_t record_bytes_per_run(const RunSpec& spec);

}  // namespace curio::lab
