// curio-lab: the experiment runner. Runs exploration campaigns (algorithms × seeds × σ)
// in-process against the simulated arm on all cores, and measures throughput.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <thread>

#include "host_tools/lab/campaign.hpp"
#include "host_tools/lab/report.hpp"
#include "host_tools/lab/scene_log.hpp"

namespace {

using namespace curio;
using namespace curio::lab;

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

struct CliOptions {
  std::string algos = "RPE,RGE-EFR,MGE-EFR";
  std::string seeds = "0-2";
  std::string noise = "0.05";
  std::string physics = "kinematic";
  std::string tie_rule = "latest";
  std::string competence = "clip";
  bool json = false;
};

// Shared between `run` and `bench`: turns the CLI strings into a campaign, or explains why not.
bool build_campaign(const CliOptions& o, CampaignConfig* c) {
  std::vector<std::string> problems;
  c->algorithms = split(o.algos, ',');
  for (auto& name : c->algorithms)  // canonical names (MGE-bVAE → MGE-βVAE) for grouping
    if (const auto algo = find_algorithm(name)) name = algo->name;
  std::string err;
  if (auto seeds = parse_seeds(o.seeds, &err)) c->seeds = *seeds;
  else problems.push_back(err);
  c->sigmas.clear();
  for (const auto& s : split(o.noise, ',')) {
    try {
      size_t used = 0;
      const double v = std::stod(s, &used);
      if (used != s.size()) throw std::invalid_argument(s);
      c->sigmas.push_back(v);
    } catch (const std::exception&) {
      problems.push_back("bad σ '" + s + "' in --noise (use e.g. 0.05 or 0.05,0.1)");
    }
  }
  if (!sim::parse_physics(o.physics, &c->physics))
    problems.push_back("unknown physics '" + o.physics + "' (kinematic or ode)");
  if (const auto t = parse_tie_rule(o.tie_rule)) c->tie_rule = *t;
  else problems.push_back("unknown --tie-rule '" + o.tie_rule + "' (earliest or latest)");
  if (const auto m = parse_competence_measure(o.competence)) c->competence_measure = *m;
  else problems.push_back("unknown --competence '" + o.competence + "' (clip or scale)");
  if (!c->seeds.empty() || problems.empty())
    for (auto& p : validate_campaign(*c)) problems.push_back(std::move(p));
  for (const auto& p : problems) std::cerr << "curio-lab: " << p << '\n';
  return problems.empty();
}

int cmd_run(const CliOptions& o, CampaignConfig c) {
  if (!build_campaign(o, &c)) return 2;
  double wall = 0.0;
  const auto results = run_campaign(c, &wall);
  const auto summary = summarize_campaign(c, results, wall);
  std::vector<std::string> warnings;
  std::string error;
  if (!write_report(c, results, summary, &warnings, &error)) {
    std::cerr << "curio-lab: " << error << '\n';
    return 1;
  }
  if (c.save_scenes && !write_scene_logs(c.out_dir, results, &error)) {
    std::cerr << "curio-lab: " << error << '\n';
    return 1;
  }
  for (const auto& w : warnings) std::cerr << "curio-lab: warning: " << w << '\n';
  if (o.json) {
    std::cout << summary.dump(2) << '\n';
  } else {
    std::cout << "\nExploration ratio (mean ± std over seeds):\n\n" << format_table(summary);
    std::printf("\nwall time %.1f s; results, CSVs and plots in %s/\n", wall, c.out_dir.c_str());
  }
  return summary["failed_runs"].get<int>() == 0 ? 0 : 1;
}

// Episodes per second of one thread's CPU time (and of wall time, which a busy machine
// inflates): the exploration loop and the physics, one MGE-EFR run.
std::pair<double, double> episodes_per_second(sim::Physics physics, int episodes) {
  RunSpec spec;
  spec.algorithm = *find_algorithm("MGE-EFR");
  spec.physics = physics;
  spec.explorer.n_bootstrap = 100;
  spec.explorer.n_episodes = episodes;
  spec.explorer.competence_cap = 1.0f;
  const RunResult r = run_exploration(spec);
  const double n = spec.explorer.n_bootstrap + spec.explorer.n_episodes;
  return {n / r.cpu_seconds, n / r.seconds};
}

int cmd_bench(const CliOptions& o, CampaignConfig c, int ode_episodes, bool skip_campaign) {
  if (!build_campaign(o, &c)) return 2;
  std::printf("curio-lab bench: one thread, MGE-EFR seed 0 (exploration loop + physics);\n"
              "  rates per CPU-second of that thread (wall-clock rate in brackets)\n");
  const auto [kin, kin_wall] = episodes_per_second(sim::Physics::kKinematic, 10000);
  std::printf("  kinematic: %10.0f episodes/s per core   (%.0f wall)\n", kin, kin_wall);
  const auto [ode, ode_wall] = episodes_per_second(sim::Physics::kOde, ode_episodes);
  std::printf("  ode:       %10.0f episodes/s per core   (%.0f wall; kinematic/ode = %.1f×)\n", ode,
              ode_wall, kin / ode);
  if (skip_campaign) return 0;
  c.quiet = true;
  double wall = 0.0;
  const auto results = run_campaign(c, &wall);
  std::printf("  campaign %zu algorithms × %zu seeds × %zu σ, %d episodes, %s physics, %d threads: "
              "%.1f s wall\n",
              c.algorithms.size(), c.seeds.size(), c.sigmas.size(), c.episodes,
              sim::physics_name(c.physics),
              c.threads > 0 ? c.threads : static_cast<int>(std::thread::hardware_concurrency()),
              wall);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "curio-lab: runs curiosity-driven exploration campaigns on the simulated Arm-2-Balls world\n"
      "(in-process, all cores) and writes exploration ratios, summaries and plots."};
  app.require_subcommand(1);
  CliOptions o;
  CampaignConfig c;
  double grasp = c.world.grasp_radius, dnoise = c.world.distractor_noise;

  auto add_common = [&](CLI::App* sub) {
    sub->add_option("--algos", o.algos, "Comma-separated algorithms: RPE, RGE-EFR, MGE-EFR, RGE-βVAE, MGE-βVAE, "
                    "MGE-βVAE-10, RGE-VAE, MGE-VAE, MGE-VAE-10 (βVAE may be spelt bVAE)")
        ->capture_default_str();
    sub->add_option("--seeds", o.seeds, "Seeds: 0-14, 0,3,7 or 1-3,8")->capture_default_str();
    sub->add_option("--noise", o.noise, "Exploration noise σ on θ; several: 0.05,0.1")
        ->capture_default_str();
    sub->add_option("--physics", o.physics, "kinematic (the paper's model) or ode (the ODE arm)")
        ->capture_default_str();
    sub->add_option("--episodes", c.episodes, "Exploration episodes after the bootstrap")
        ->capture_default_str();
    sub->add_option("--bootstrap", c.bootstrap,
                    "Random episodes first (default: 100 for EFR, 400 for learned goal spaces)");
    sub->add_option("--competence-clip", c.competence_clip,
                    "D of SPEC §2.5 (default: 1 for EFR, reproducing the archived runs; 2 for "
                    "learned goal spaces)");
    sub->add_option("--competence", o.competence,
                    "How D enters the competence of SPEC §2.5: clip (-min(|g-r|, D), SPEC as "
                    "written) or scale (-|g-r|/D, explauto's competence_dist as the reference ran it)")
        ->capture_default_str();
    sub->add_option("--window", c.window, "W of SPEC §2.5 (interest smoothing)")->capture_default_str();
    sub->add_option("--epsilon", c.epsilon, "Share of uniform module choice")->capture_default_str();
    sub->add_option("--grasp-radius", grasp, "Grasp radius")->capture_default_str();
    sub->add_option("--distractor-noise", dnoise, "Distractor random-walk std per step")
        ->capture_default_str();
    sub->add_option("--tie-rule", o.tie_rule,
                    "Which archive entry wins a 1-NN tie: latest (tracks the reference implementation; docs/reproduction.md) or earliest")
        ->capture_default_str();
    sub->add_option("--threads", c.threads, "Worker threads (0: all cores)")->capture_default_str();
  };

  auto* run = app.add_subcommand("run", "Run a campaign and write CSV, JSON and PNG results");
  add_common(run);
  run->add_option("--out", c.out_dir, "Output folder")->capture_default_str();
  run->add_flag("--json", o.json, "Print the JSON summary to stdout instead of the table");
  run->add_flag("--quiet", c.quiet, "No progress lines");
  run->add_flag("--save-scenes", c.save_scenes,
                "Also write runs/<run>_scenes.csv: every episode's final ball and distractor "
                "position (training data for curio-train train --scenes)");

  auto* bench = app.add_subcommand(
      "bench", "Episodes/s per core for each physics, then the wall time of a campaign "
               "(default 3 algorithms × 15 seeds, kinematic)");
  add_common(bench);
  int ode_episodes = 2000;
  bool skip_campaign = false;
  bench->add_option("--ode-episodes", ode_episodes, "Episodes of the ODE throughput run")
      ->capture_default_str();
  bench->add_flag("--no-campaign", skip_campaign, "Only the per-core throughput");

  auto* paper = app.add_subcommand(
      "paper",
      "The paper's whole figure as one campaign: RPE, RGE-EFR, MGE-EFR, RGE-VAE, MGE-VAE, "
      "RGE-βVAE, MGE-βVAE (+ the 10-module MGE-VAE-10 and MGE-βVAE-10 for the interest plots) "
      "× seeds × σ ∈ {0.05, 0.1}; learned goal spaces need the trained weight headers. "
      "Unless given, --algos is all nine, --seeds 0-14, --noise 0.05,0.1 and --out out/paper "
      "(the defaults printed below are `run`'s)");
  add_common(paper);
  paper->add_option("--out", c.out_dir, "Output folder")->capture_default_str();
  paper->add_flag("--json", o.json, "Print the JSON summary to stdout instead of the table");
  paper->add_flag("--quiet", c.quiet, "No progress lines");
  bool efr_only = false;
  paper->add_flag("--efr-only", efr_only, "Only RPE, RGE-EFR, MGE-EFR (no trained weights needed)");

  CLI11_PARSE(app, argc, argv);
  c.world.grasp_radius = grasp;
  c.world.distractor_noise = dnoise;
  if (run->parsed()) return cmd_run(o, c);
  if (paper->parsed()) {
    if (paper->get_option("--algos")->count() == 0)
      o.algos = efr_only ? "RPE,RGE-EFR,MGE-EFR"
                         : "RPE,RGE-EFR,MGE-EFR,RGE-VAE,MGE-VAE,RGE-βVAE,MGE-βVAE,MGE-VAE-10,"
                           "MGE-βVAE-10";
    if (paper->get_option("--seeds")->count() == 0) o.seeds = "0-14";
    if (paper->get_option("--noise")->count() == 0) o.noise = "0.05,0.1";
    if (paper->get_option("--out")->count() == 0) c.out_dir = "out/paper";
    return cmd_run(o, c);
  }
  if (bench->count_all() > 0 || bench->parsed()) {
    if (bench->get_option("--seeds")->count() == 0) o.seeds = "0-14";
    return cmd_bench(o, c, ode_episodes, skip_campaign);
  }
  return 2;
}
