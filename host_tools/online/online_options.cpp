#include "host_tools/online/online_options.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "firmware/explore/config.hpp"
#include "host_tools/cli/command_line.hpp"
#include "host_tools/experiment/explore_strategies.hpp"

namespace curio::online {

std::vector<int> OnlineOptions::retrain_points() const {
  std::vector<int> points{bootstrap};
  if (retrain_every > 0)
    for (int e = bootstrap + retrain_every; e <= last_retrain && e < bootstrap + episodes;
         e += retrain_every)
      points.push_back(e);
  return points;
}

int OnlineOptions::open_latents_at(double c) const {
  if (!progressive()) return 10;
  // The small slack keeps C exactly at a group's capacity (6 nats = 2 latents × 3) from
  // opening the next group through rounding.
  const int groups = static_cast<int>(std::ceil(c / (group_size * nats_per_latent) - 1e-9));
  return std::min(10, group_size * std::max(1, groups));
}

void add_options(CLI::App& app, CommandLine& cl) {
  OnlineOptions& o = cl.options;
  app.add_option("--out", o.out_dir, "Output folder (options.json, checkpoints, reports, figures)")
      ->check(curio::cli::kOutputFolder)
      ->capture_default_str();
  app.add_flag("--resume", o.resume,
               "Continue the run in --out from its last checkpoint, with its own options.json "
               "(an interrupted run gives the same results as an uninterrupted one)");
  app.add_option("--seed", o.seed, "Run seed (explorer, world, training)")
      ->check(cli::kSeed)->capture_default_str();
  app.add_option("--episodes", o.episodes, "Episodes after the 400 random bootstrap episodes (multiple of 5)")
      ->capture_default_str();
  // A typed choice: IsMember refuses anything but the two names while parsing, and the name
  // lands in the enum.
  app.add_option_function<std::string>(
         "--physics", [&o](const std::string& name) { sim::parse_physics(name, &o.physics); }, "Arm simulation")
      ->check(CLI::IsMember({sim::physics_name(sim::Physics::kKinematic), sim::physics_name(sim::Physics::kOde)}))
      ->default_str(sim::physics_name(o.physics));
  // The passive baseline runs the same strategy.
  lab::add_exploration_options(&app, &cl.exploration, lab::ExplorationSet::kStrategyOnly);
  app.add_option("--retrain-every", o.retrain_every,
                 "Episodes between retrains, up to episode 6,400 (multiple of 5; 0: train once)")
      ->check(cli::kNonNegative)->capture_default_str();
  app.add_option("--first-iterations", o.first_iterations, "Training iterations at the end of the bootstrap")
      ->check(cli::kPositive)->capture_default_str();
  app.add_option("--retrain-iterations", o.retrain_iterations, "Training iterations at each retrain (warm start)")
      ->check(cli::kNonNegative)->capture_default_str();
  app.add_option("--novelty-fraction", o.novelty_fraction,
                 "Share of goal-exploration steps that explore around an episode whose image the model "
                 "reconstructs worst (0: off)")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  app.add_option("--anchor-weight", o.anchor_weight,
                 "A training that opens latents keeps the open ones' code at this weight (0: off)")
      ->check(cli::kNonNegative)->capture_default_str();
  app.add_flag_callback("--no-baselines", [&o] { o.baselines = false; },
                        "Skip the passive MGE-βVAE and RPE runs at the end");
  app.add_option("--export-codes", cl.export_round,
                 "Write <out>/codes_round_R.csv, the μ round R's model gives every scene of the run in "
                 "--out (beside the true positions, for analysis), and exit")
      ->check(cli::kNonNegative);
  app.add_option("--threads", o.threads, "LibTorch and rendering threads (results are bit-exact per count)")
      ->check(CLI::Range(1, 256))->capture_default_str();
  app.add_flag("--quiet", o.quiet, "No progress lines");
  app.add_option("--stop-after-retrain", o.stop_after_retrain,
                 "Stop after this round's checkpoint, as if interrupted (tests; -1: never)")
      ->check(CLI::Range(-1, 1000))->capture_default_str();
}

void take_exploration_options(CommandLine* cl) { cl->options.explore = cl->exploration.explore; }

std::string command_line_problem(const CLI::App& app, const CommandLine& cl) {
  if (!cl.options.resume && cl.export_round < 0) return "";
  const char* mode = cl.options.resume ? "--resume" : "--export-codes";
  if (cl.options.resume && cl.export_round >= 0) return "--export-codes: not with --resume";
  for (const char* name : {"--seed", "--episodes", "--physics", "--retrain-every", "--first-iterations",
                           "--retrain-iterations", "--novelty-fraction", "--anchor-weight", "--no-baselines", "--explore"})
    if (app.count(name) > 0)
      return fmt::format("{}: not with {} (the run's options.json governs)", name, mode);
  return "";
}

// Every field of options.json. `since_first` are the fields of the first version (required);
// `later` were added after it, with the value that reproduces a run that predates them.
#define CURIO_ONLINE_FIELDS(X)                                                                \
  X(seed) X(sigma) X(bootstrap) X(episodes) X(group_size) X(competence_cap)                    \
  X(retrain_every) X(last_retrain) X(first_iterations) X(retrain_iterations) X(beta)          \
  X(capacity_max) X(capacity_iters) X(batch) X(lr) X(out_init_scale) X(eval_images)            \
  X(interest_every) X(progress_every) X(baselines)
#define CURIO_ONLINE_LATER_FIELDS(X)                                                          \
  X(nats_per_latent, 0.0) X(release_scale, 0.3) X(novelty_fraction, 0.0) X(novelty_top, 0.02) \
  X(anchor_weight, 0.0)

nlohmann::json to_json(const OnlineOptions& o) {
  nlohmann::json j;
#define X(f) j[#f] = o.f;
  CURIO_ONLINE_FIELDS(X)
#undef X
#define X(f, before) j[#f] = o.f;
  CURIO_ONLINE_LATER_FIELDS(X)
#undef X
  j["physics"] = sim::physics_name(o.physics);
  if (o.explore != "spec") j["explore"] = o.explore;
  return j;
}

OnlineOptions options_from_json(const nlohmann::json& j) {
  OnlineOptions o;
#define X(f) o.f = j.at(#f).get<decltype(o.f)>();
  CURIO_ONLINE_FIELDS(X)
#undef X
#define X(f, before) o.f = j.value(#f, decltype(o.f){before});
  CURIO_ONLINE_LATER_FIELDS(X)
#undef X
  const auto physics = j.at("physics").get<std::string>();
  if (!sim::parse_physics(physics, &o.physics)) throw std::runtime_error("options.json: unknown physics " + physics);
  o.explore = j.value("explore", std::string("spec"));
  return o;
}

std::string removed_option_in(const nlohmann::json& j) {
  // The options removed after be4b2e6, each with the value that kept it off (its default there).
  static const std::map<std::string, nlohmann::json> removed{
      {"unmix", false},           {"surprise_fraction", 0.0}, {"surprise_top", 0.05},
      {"skew_alpha", 0.0},        {"skew_neighbours", 10},    {"skew_cap", 20.0},
      {"kl_penalty", "abs"},      {"kl_weight", 0.0},         {"decoder", "spec"},
      {"goal_modules", "groups"}, {"goal_scale", 1.0}};
  const std::set<std::string> known = [] {
    std::set<std::string> k{"physics", "explore"};
#define X(f) k.insert(#f);
    CURIO_ONLINE_FIELDS(X)
#undef X
#define X(f, before) k.insert(#f);
    CURIO_ONLINE_LATER_FIELDS(X)
#undef X
    return k;
  }();
  for (const auto& [key, value] : j.items()) {
    if (known.count(key) > 0) continue;
    const auto r = removed.find(key);
    if (r == removed.end()) return fmt::format("options.json has a field this version does not know: {}", key);
    if (value != r->second)
      return fmt::format("options.json sets {} = {}, an option this version no longer has (only {}); "
                         "run it with the commit be4b2e6",
                         key, value.dump(), r->second.dump());
  }
  return "";
}

std::string check(const OnlineOptions& o) {
  if (o.episodes < 5 || o.episodes % 5 != 0) return "--episodes must be a positive multiple of 5";
  if (o.bootstrap < 1) return "bootstrap (options.json) must be >= 1 (the first training needs images)";
  if (o.bootstrap + o.episodes > kArchiveCapacity)
    return fmt::format("--episodes: {} + the {} bootstrap episodes exceed the archive capacity {}", o.episodes,
                       o.bootstrap, kArchiveCapacity);
  if (o.retrain_every < 0 || o.retrain_every % 5 != 0)
    return "--retrain-every must be >= 0 and a multiple of 5 (retrains fall between steps)";
  if (o.first_iterations < 1) return "--first-iterations must be >= 1";
  if (o.retrain_iterations < 0) return "--retrain-iterations must be >= 0";
  if (!(o.novelty_fraction >= 0 && o.novelty_fraction <= 1)) return "--novelty-fraction must be in [0, 1]";
  if (!(o.anchor_weight >= 0)) return "--anchor-weight must be >= 0 (0: off)";
  if (o.anchor_weight > 0 && !o.progressive())
    return "--anchor-weight needs progressive latents (nats_per_latent > 0 in options.json): it anchors the "
           "latents open before a training opens more";
  if (!lab::find_explore_strategy(o.explore))
    return fmt::format("--explore: unknown strategy '{}' (known: {})", o.explore, lab::explore_strategy_names());
  if (o.threads < 1) return "--threads must be >= 1";
  // The recipe: set by options.json only.
  if (o.group_size < 1 || 10 % o.group_size != 0) return "group_size (options.json) must divide 10";
  if (o.batch < 1 || o.batch > o.bootstrap) return "batch (options.json) must be in 1..bootstrap";
  if (!(o.lr > 0) || !(o.beta >= 0) || !(o.capacity_max >= 0) || o.capacity_iters < 1)
    return "options.json: lr must be > 0, beta and capacity_max >= 0, capacity_iters >= 1";
  if (!(o.sigma >= 0) || !(o.competence_cap > 0)) return "options.json: sigma must be >= 0 and competence_cap > 0";
  if (o.eval_images < 10) return "eval_images (options.json) must be >= 10";
  if (o.interest_every < 1 || o.progress_every < 1)
    return "options.json: interest_every and progress_every must be >= 1";
  if (!(o.nats_per_latent >= 0) || !(o.release_scale > 0))
    return "options.json: nats_per_latent must be >= 0 (0: off) and release_scale > 0";
  if (!(o.novelty_top > 0 && o.novelty_top <= 1)) return "novelty_top (options.json) must be in (0, 1]";
  return "";
}

}  // namespace curio::online
