#include "host_tools/lab/bench_command.hpp"

#include <algorithm>
#include <cstdio>
#include <thread>
#include <utility>

#include "host_tools/cli/command_line.hpp"
#include "host_tools/experiment/simulated_run.hpp"
#include "host_tools/lab/campaign_runner.hpp"
#include "host_tools/lab/slurm_jobs.hpp"

namespace curio::lab {

namespace {

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

// Resource advice per algorithm and physics (docs/cluster.md): one run of each.
void print_per_algorithm(const CampaignConfig& c, int ode_episodes) {
  std::printf(
      "  per algorithm, one run each (%d kinematic / %d ode episodes), episodes/s per "
      "CPU-second:\n",
      c.episodes, ode_episodes);
  CampaignConfig k = c, d = c;
  k.physics = sim::Physics::kKinematic;
  d.physics = sim::Physics::kOde;
  d.episodes = ode_episodes;
  const auto kin_rates = cpu_seconds_per_episode(k, k.episodes);
  const auto ode_rates = cpu_seconds_per_episode(d, d.episodes);
  for (size_t i = 0; i < kin_rates.size(); ++i) {
    std::string name = kin_rates[i].first;  // padded by characters (β is two bytes)
    const auto width =
        std::count_if(name.begin(), name.end(), [](char ch) { return (ch & 0xC0) != 0x80; });
    name.append(static_cast<size_t>(std::max<std::ptrdiff_t>(12 - width, 0)), ' ');
    std::printf("    %s kinematic %8.0f   ode %6.0f\n", name.c_str(), 1.0 / kin_rates[i].second,
                1.0 / ode_rates[i].second);
  }
}

}  // namespace

CLI::App* add_bench_command(CLI::App& app, CampaignOptions& campaign, BenchCommandOptions& o) {
  auto* bench =
      app.add_subcommand("bench",
                         "Episodes/s per core for each physics, then the wall time of a campaign "
                         "(default 3 algorithms × 15 seeds, kinematic)");
  add_campaign_options(bench, campaign);
  bench->add_option("--ode-episodes", o.ode_episodes, "Episodes of the ODE throughput run")
      ->capture_default_str();
  bench->add_flag("--no-campaign", o.skip_campaign, "Only the per-core throughput");
  bench->add_flag("--per-algorithm", o.per_algorithm,
                  "Also the rate of each of --algos, kinematic and ode (one run each)");
  return bench;
}

int bench_command(const CLI::App& command, CampaignOptions campaign, const BenchCommandOptions& o) {
  if (command.get_option("--seeds")->count() == 0) campaign.seeds = "0-14";
  CampaignConfig c;
  std::string problem;
  if (!build_campaign(campaign, &c, &problem)) return cli::usage_error(command, problem);
  if (o.ode_episodes < 5 || o.ode_episodes % 5 != 0)
    return cli::usage_error(command, "--ode-episodes must be a positive multiple of 5 (got " +
                                         std::to_string(o.ode_episodes) + ")");
  std::printf(
      "curio-lab bench: one thread, MGE-EFR seed 0 (exploration loop + physics);\n"
      "  rates per CPU-second of that thread (wall-clock rate in brackets)\n");
  const auto [kin, kin_wall] = episodes_per_second(sim::Physics::kKinematic, 10000);
  std::printf("  kinematic: %10.0f episodes/s per core   (%.0f wall)\n", kin, kin_wall);
  const auto [ode, ode_wall] = episodes_per_second(sim::Physics::kOde, o.ode_episodes);
  std::printf("  ode:       %10.0f episodes/s per core   (%.0f wall; kinematic/ode = %.1f×)\n", ode,
              ode_wall, kin / ode);
  if (o.per_algorithm) print_per_algorithm(c, o.ode_episodes);
  if (o.skip_campaign) return 0;
  c.quiet = true;
  double wall = 0.0;
  run_campaign(c, &wall);
  std::printf(
      "  campaign %zu algorithms × %zu seeds × %zu σ, %d episodes, %s physics, %d threads: "
      "%.1f s wall\n",
      c.algorithms.size(), c.seeds.size(), c.sigmas.size(), c.episodes,
      sim::physics_name(c.physics),
      c.threads > 0 ? c.threads : static_cast<int>(std::thread::hardware_concurrency()), wall);
  return 0;
}

}  // namespace curio::lab
