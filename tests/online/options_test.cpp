// curio-online's options (online_options.hpp): the defaults are the best measured configuration
// ("anc" in docs/online.md) field for field; an options.json of that configuration, written by
// an earlier version, resumes unchanged, while one that sets a removed option to anything but
// its old default, or a field this version does not know, is refused; the command line has at
// most 16 options, a typed --physics, and refuses run options beside --resume.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "host_tools/online/online_options.hpp"

namespace curio::online {
namespace {

// The options.json of the anc configuration's seed-0 run (archive checksum c8114787, ratio
// .568 at 9,666 episodes) as an earlier version wrote it, with three options since removed at
// their defaults.
const char* const kAncOptionsJson = R"({
  "baselines": true, "batch": 32, "beta": 150.0, "bootstrap": 400, "capacity_iters": 12000,
  "capacity_max": 12.0, "competence_cap": 2.0, "episodes": 10000, "eval_images": 2000,
  "first_iterations": 6000, "group_size": 2, "interest_every": 50, "last_retrain": 6400,
  "lr": 0.0005, "nats_per_latent": 3.0, "novelty_fraction": 0.3, "novelty_top": 0.02,
  "out_init_scale": 0.01, "physics": "kinematic", "progress_every": 500, "release_scale": 0.3,
  "retrain_every": 1000, "retrain_iterations": 2000, "seed": 0, "sigma": 0.05,
  "surprise_fraction": 0.0, "surprise_top": 0.05, "unmix": false, "anchor_weight": 10.0
})";

TEST(OnlineOptions, DefaultsAreTheAncConfiguration) {
  const OnlineOptions o;
  EXPECT_EQ(o.nats_per_latent, 3.0);
  EXPECT_EQ(o.novelty_fraction, 0.3);
  EXPECT_EQ(o.anchor_weight, 10.0);
  nlohmann::json anc = nlohmann::json::parse(kAncOptionsJson);
  for (const char* removed : {"surprise_fraction", "surprise_top", "unmix"}) anc.erase(removed);
  EXPECT_EQ(to_json(o), anc) << to_json(o).dump(2);
  EXPECT_EQ(check(o), "");
}

TEST(OnlineOptions, TheAncRunsOptionsResumeAsTheDefaults) {
  const nlohmann::json anc = nlohmann::json::parse(kAncOptionsJson);
  EXPECT_EQ(removed_option_in(anc), "");
  EXPECT_EQ(to_json(options_from_json(anc)), to_json(OnlineOptions{}));
}

TEST(OnlineOptions, RemovedOptionsSetToAnythingButTheirOldDefaultAreRefused) {
  for (const auto& [key, value] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"surprise_fraction", 0.5}, {"unmix", true}, {"skew_alpha", -1.0}, {"kl_penalty", "hinge"},
           {"kl_weight", 20.0}, {"decoder", "additive"}, {"goal_modules", "open-singles"}, {"goal_scale", 2.5}}) {
    nlohmann::json j = nlohmann::json::parse(kAncOptionsJson);
    j[key] = value;
    const std::string why = removed_option_in(j);
    EXPECT_NE(why.find(key), std::string::npos) << why;
    EXPECT_NE(why.find("be4b2e6"), std::string::npos) << why;
  }
  nlohmann::json j = nlohmann::json::parse(kAncOptionsJson);
  j["goal_scale"] = 1;  // the old default, written as an integer: still the prior
  j["decoder"] = "spec";
  EXPECT_EQ(removed_option_in(j), "");
  j["warp_drive"] = true;
  EXPECT_NE(removed_option_in(j).find("warp_drive"), std::string::npos);
}

TEST(OnlineOptions, RunsThatPredateAFeatureResumeWithItOff) {
  nlohmann::json j = nlohmann::json::parse(kAncOptionsJson);
  for (const char* later : {"nats_per_latent", "release_scale", "novelty_fraction", "novelty_top", "anchor_weight"})
    j.erase(later);
  const OnlineOptions o = options_from_json(j);
  EXPECT_FALSE(o.progressive());
  EXPECT_EQ(o.novelty_fraction, 0.0);
  EXPECT_EQ(o.anchor_weight, 0.0);
  j.erase("physics");
  EXPECT_ANY_THROW(options_from_json(j));
}

TEST(OnlineOptions, CheckNamesTheOption) {
  OnlineOptions o;
  o.episodes = 7;
  EXPECT_EQ(check(o).rfind("--episodes", 0), 0u) << check(o);
  o = OnlineOptions{};
  o.retrain_every = 12;
  EXPECT_EQ(check(o).rfind("--retrain-every", 0), 0u) << check(o);
  o = OnlineOptions{};
  o.nats_per_latent = 0.0;  // anchoring needs progressive latents
  EXPECT_EQ(check(o).rfind("--anchor-weight", 0), 0u) << check(o);
}

TEST(OnlineOptions, TheStrategyIsWrittenOnlyWhenItIsNotSpecsAndUnknownOnesAreRefused) {
  OnlineOptions o;
  EXPECT_FALSE(to_json(o).contains("explore"));  // a spec run's options.json is as before
  o.explore = "beyond";
  const nlohmann::json j = to_json(o);
  EXPECT_EQ(j.at("explore"), "beyond");
  EXPECT_EQ(removed_option_in(j), "");
  EXPECT_EQ(options_from_json(j).explore, "beyond");
  EXPECT_EQ(options_from_json(nlohmann::json::parse(kAncOptionsJson)).explore, "spec");
  o.explore = "frontier-ish";
  EXPECT_EQ(check(o).rfind("--explore: unknown strategy 'frontier-ish' (known: spec, beyond", 0), 0u) << check(o);
}

// Parses `args` with curio-online's options; returns the CLI11 error text ("" when it parsed).
std::string parse(CommandLine& cl, CLI::App& app, std::vector<std::string> args) {
  add_options(app, cl);
  std::reverse(args.begin(), args.end());  // CLI11 takes a vector in reverse order
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return "";
}

TEST(OnlineOptions, CommandLineHasAtMost16OptionsAndATypedPhysics) {
  CommandLine cl;
  CLI::App app;
  EXPECT_EQ(parse(cl, app, {"--physics", "ode", "--seed", "4"}), "");
  EXPECT_EQ(cl.options.physics, sim::Physics::kOde);
  EXPECT_EQ(cl.options.seed, 4u);
  EXPECT_EQ(to_json(cl.options)["physics"], "ode");
  const auto options = app.get_options([](const CLI::Option* o) { return o->get_name() != "--help"; });
  EXPECT_LE(options.size(), 16u);
  CommandLine bad;
  CLI::App bad_app;
  EXPECT_NE(parse(bad, bad_app, {"--physics", "odd"}).find("--physics"), std::string::npos);
}

TEST(OnlineOptions, ResumeTakesOnlyThisProcesssOptions) {
  {
    CommandLine cl;
    CLI::App app;
    ASSERT_EQ(parse(cl, app, {"--resume", "--out", "x", "--threads", "2", "--quiet"}), "");
    EXPECT_EQ(command_line_problem(app, cl), "");
  }
  {
    CommandLine cl;
    CLI::App app;
    ASSERT_EQ(parse(cl, app, {"--resume", "--episodes", "100"}), "");
    EXPECT_EQ(command_line_problem(app, cl).rfind("--episodes", 0), 0u) << command_line_problem(app, cl);
  }
  {
    CommandLine cl;
    CLI::App app;
    ASSERT_EQ(parse(cl, app, {"--export-codes", "2", "--no-baselines"}), "");
    EXPECT_EQ(command_line_problem(app, cl).rfind("--no-baselines", 0), 0u) << command_line_problem(app, cl);
  }
  {
    CommandLine cl;
    CLI::App app;
    ASSERT_EQ(parse(cl, app, {"--resume", "--explore", "beyond"}), "");
    EXPECT_EQ(command_line_problem(app, cl).rfind("--explore", 0), 0u) << command_line_problem(app, cl);
  }
}

}  // namespace
}  // namespace curio::online
