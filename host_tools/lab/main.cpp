// curio-lab: the experiment runner. Runs exploration campaigns (algorithms × seeds × σ)
// in-process against the simulated arm on all cores, and measures throughput.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <thread>

#include "host_tools/experiment/campaign_config.hpp"
#include "host_tools/lab/campaign_merge.hpp"
#include "host_tools/lab/campaign_task.hpp"
#include "host_tools/lab/local_campaign.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/lab/scene_log.hpp"
#include "host_tools/lab/slurm_jobs.hpp"

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

// Ctrl-C (SIGINT) and SIGTERM: the campaign stops cleanly (finished runs are on disk, runs in
// flight end before their next episode); a second signal kills at once (SA_RESETHAND).
std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_signal = 0;
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

extern "C" void on_stop_signal(int sig) {
  g_signal = sig;
  g_stop.store(true);
}

void install_stop_handlers() {
  struct sigaction sa = {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

const char* signal_name(int sig) {
  return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}

struct CliOptions {
  std::string algos = "RPE,RGE-EFR,MGE-EFR";
  std::string seeds = "0-2";
  std::string noise = "0.05";
  std::string physics = "kinematic";
  std::string tie_rule = "latest";
  std::string competence = "clip";
  bool json = false;
  bool replace = false;  // run/paper --replace (local_campaign.hpp)
  bool no_journal = false;
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

// Writes the report of a campaign's results and prints its table (run, paper and merge):
// 1 when a file cannot be written (*written false) or a run failed.
int write_and_print(const CliOptions& o, const CampaignConfig& c,
                    const std::vector<RunResult>& results, const nlohmann::json& summary,
                    double wall, bool* written = nullptr, bool scenes_written = false) {
  std::vector<std::string> warnings;
  std::string error;
  const bool ok = write_report(c, results, summary, &warnings, &error);
  if (written) *written = ok;
  if (!ok) {
    std::cerr << "curio-lab: " << error << '\n';
    return 1;
  }
  if (c.save_scenes && !scenes_written && !write_scene_logs(c.out_dir, results, &error)) {
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

int cmd_run(const CliOptions& o, CampaignConfig c) {
  if (!build_campaign(o, &c)) return 2;
  install_stop_handlers();
  LocalCampaignOptions lo;
  lo.replace = o.replace;
  lo.journal = !o.no_journal;
  lo.log = stderr;
  lo.stop = &g_stop;
  std::vector<RunResult> results;
  LocalCampaignOutcome out;
  std::string error;
  const auto status = run_local_campaign(c, lo, &results, &out, &error);
  if (status != LocalCampaignStatus::kOk) {
    std::cerr << "curio-lab: " << error << '\n';
    return status == LocalCampaignStatus::kRefused ? 2 : 1;
  }
  if (g_stop.load()) {
    const int sig = g_signal;
    std::fprintf(stderr,
                 "curio-lab: stopped by %s: %zu of %zu runs finished and recorded in %s/records "
                 "(%zu this time, %zu before); %zu runs not finished. Run the same command again "
                 "to resume (finished runs are skipped), or `curio-lab merge %s --out DIR "
                 "--allow-partial` for a report of the finished ones\n",
                 signal_name(sig), out.skipped + out.ran, out.runs, c.out_dir.c_str(), out.ran,
                 out.skipped, out.runs - out.skipped - out.ran, c.out_dir.c_str());
    return 128 + (sig > 0 ? sig : SIGINT);
  }
  return write_and_print(o, c, results, summarize_campaign(c, results, out.wall_seconds),
                         out.wall_seconds, nullptr, true);
}

// `run --task I --tasks N`: only slice I of N, into a task folder for `merge` (campaign_task.hpp).
int cmd_run_task(const CliOptions& o, CampaignConfig c, int task, int tasks) {
  if (!build_campaign(o, &c)) return 2;
  if (tasks < 1 || task < 0 || task >= tasks) {
    std::cerr << "curio-lab: --task must be in [0, --tasks) (got " << task << " of " << tasks << ")\n";
    return 2;
  }
  if (o.replace) {
    std::cerr << "curio-lab: --replace is for a local run; a task folder of another campaign "
                 "is refused (use another --out)\n";
    return 2;
  }
  install_stop_handlers();
  TaskOutcome out;
  std::string error;
  if (!run_task(c, task, tasks, &out, &error, &g_stop)) {
    std::cerr << "curio-lab: " << error << '\n';
    return 1;
  }
  if (g_stop.load()) {
    std::fprintf(stderr,
                 "curio-lab: stopped by %s: task %d of %d has %zu of %zu runs recorded in "
                 "%s/records; run it again to resume (recorded runs are skipped)\n",
                 signal_name(g_signal), task, tasks, out.runs - out.stopped, out.runs,
                 c.out_dir.c_str());
    return 128 + (g_signal > 0 ? g_signal : SIGINT);
  }
  std::printf("task %d of %d: %zu runs (%zu already recorded, skipped; %zu failed) in %.1f s; "
              "records in %s/\n",
              task, tasks, out.runs, out.skipped, out.failed, out.wall_seconds, c.out_dir.c_str());
  return out.failed == 0 ? 0 : 1;
}

// `merge DIR...`: task folders back into one campaign's report (campaign_merge.hpp).
int cmd_merge(const CliOptions& o, const std::vector<std::string>& dirs, const std::string& out_dir,
              bool allow_partial) {
  std::string error;
  auto merged = merge_tasks(dirs, &error);
  if (!merged) {
    std::cerr << "curio-lab merge: " << error << '\n';
    return 2;
  }
  const size_t expected = expand_runs(merged->config).size();
  for (const auto& m : merged->missing) std::cerr << "curio-lab merge: missing " << m << '\n';
  for (const auto& f : merged->failed) std::cerr << "curio-lab merge: failed " << f << '\n';
  const bool partial = !merged->missing.empty() || !merged->failed.empty();
  if (partial && !allow_partial) {
    std::cerr << "curio-lab merge: " << merged->missing.size() << " of " << expected
              << " runs missing, " << merged->failed.size()
              << " failed: nothing written (resubmit, or --allow-partial)\n";
    return 1;
  }
  CampaignConfig c = merged->config;
  c.out_dir = out_dir;
  auto summary = summarize_campaign(c, merged->results, merged->run_seconds);
  if (!merged->missing.empty()) summary["missing_runs"] = merged->missing;
  if (!o.json)
    std::printf("curio-lab merge: %zu of %zu runs from %d task folders (wall time below: the "
                "runs' own, summed)\n",
                merged->results.size(), expected, merged->tasks);
  bool written = false;
  const int rc = write_and_print(o, c, merged->results, summary, merged->run_seconds, &written);
  return written && partial ? 0 : rc;  // failed runs were accepted with --allow-partial
}

struct SlurmCli {
  std::string out;
  int chunk = 10;
  bool submit = false;
  std::string binary;
  SlurmResources resources;
};

// Submits what write_*_job wrote, printing the job ids; 1 when sbatch fails.
int submit_jobs(const SlurmJobFiles& f, bool with_merge) {
  std::string error;
  std::optional<std::string> array;
  if (!f.array_script.empty()) {
    array = sbatch({}, f.array_script, &error);
    if (!array) {
      std::cerr << "curio-lab: " << error << '\n';
      return 1;
    }
    std::printf("submitted array job %s (indices %s)\n", array->c_str(), array_spec(f.array).c_str());
  }
  if (!with_merge) return 0;
  std::vector<std::string> dep;
  if (array) dep = {"--dependency=afterok:" + *array, "--kill-on-invalid-dep=yes"};
  const auto merge = sbatch(dep, f.merge_script, &error);
  if (!merge) {
    std::cerr << "curio-lab: " << error << '\n';
    return 1;
  }
  std::printf("submitted merge job %s%s\n", merge->c_str(),
              array ? (" (after array job " + *array + " succeeds)").c_str() : "");
  return 0;
}

std::string this_binary() {
  std::error_code ec;
  const auto p = std::filesystem::canonical("/proc/self/exe", ec);
  return ec ? "curio-lab" : p.string();
}

int cmd_slurm(const CliOptions& o, CampaignConfig c, const SlurmCli& s) {
  if (!build_campaign(o, &c)) return 2;
  if (s.chunk < 1 || s.resources.cpus < 1) {
    std::cerr << "curio-lab: --chunk and --cpus must be ≥ 1\n";
    return 2;
  }
  CampaignJobRequest q;
  q.config = c;
  q.run_options = campaign_run_options(c);
  q.out_dir = std::filesystem::absolute(s.out).lexically_normal().string();
  q.binary = s.binary.empty() ? this_binary() : s.binary;
  q.chunk = s.chunk;
  q.resources = s.resources;
  if (q.resources.job_name.empty()) q.resources.job_name = "curio-lab";
  SlurmJobFiles f;
  std::string error;
  if (!write_campaign_job(q, &f, &error)) {
    std::cerr << "curio-lab: " << error << '\n';
    return 2;
  }
  std::printf("curio-lab slurm: %zu runs in %d tasks; %zu to run (%s), time %s per task (%s)\n"
              "  scripts in %s/ (submit.sh submits them); results will be in %s/\n",
              expand_runs(c).size(), f.tasks, f.array.size(),
              f.array.empty() ? "none: every task is complete" : array_spec(f.array).c_str(),
              f.time.c_str(), f.time_basis.c_str(), f.dir.c_str(), q.out_dir.c_str());
  return s.submit ? submit_jobs(f, true) : 0;
}

int cmd_slurm_train(const SlurmCli& s, const std::string& script, const std::string& seeds,
                    const std::string& trainer, const std::string& done_file) {
  TrainJobRequest q;
  std::string error;
  const auto parsed = parse_seeds(seeds, &error);
  if (!parsed) {
    std::cerr << "curio-lab: " << error << '\n';
    return 2;
  }
  q.seeds = *parsed;
  std::error_code ec;
  q.script = std::filesystem::canonical(script, ec).string();
  if (ec) {
    std::cerr << "curio-lab: no training script " << script << '\n';
    return 2;
  }
  q.out_dir = std::filesystem::absolute(s.out).lexically_normal().string();
  q.trainer = trainer;
  if (q.trainer.empty()) {  // the trainer built beside this curio-lab, if there is one
    const auto sibling =
        std::filesystem::path(this_binary()).parent_path().parent_path() / "train" / "curio-train";
    if (std::filesystem::exists(sibling)) q.trainer = sibling.string();
  }
  q.done_file = done_file;
  q.resources = s.resources;
  if (q.resources.job_name.empty()) q.resources.job_name = "curio-train";
  if (q.resources.time.empty()) q.resources.time = "2:00:00";
  SlurmJobFiles f;
  if (!write_train_job(q, &f, &error)) {
    std::cerr << "curio-lab: " << error << '\n';
    return 2;
  }
  std::printf("curio-lab slurm-train: %d seeds; %zu to train (%s), time %s each\n"
              "  scripts in %s/ (submit.sh submits them); seed S trains in %s/seed-S/\n",
              f.tasks, f.array.size(),
              f.array.empty() ? "none: every seed is finished" : array_spec(f.array).c_str(),
              q.resources.time.c_str(), f.dir.c_str(), q.out_dir.c_str());
  return s.submit ? submit_jobs(f, false) : 0;
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

int cmd_bench(const CliOptions& o, CampaignConfig c, int ode_episodes, bool skip_campaign,
              bool per_algorithm) {
  if (!build_campaign(o, &c)) return 2;
  std::printf("curio-lab bench: one thread, MGE-EFR seed 0 (exploration loop + physics);\n"
              "  rates per CPU-second of that thread (wall-clock rate in brackets)\n");
  const auto [kin, kin_wall] = episodes_per_second(sim::Physics::kKinematic, 10000);
  std::printf("  kinematic: %10.0f episodes/s per core   (%.0f wall)\n", kin, kin_wall);
  const auto [ode, ode_wall] = episodes_per_second(sim::Physics::kOde, ode_episodes);
  std::printf("  ode:       %10.0f episodes/s per core   (%.0f wall; kinematic/ode = %.1f×)\n", ode,
              ode_wall, kin / ode);
  if (per_algorithm) {
    // Resource advice per algorithm and physics (docs/cluster.md): one run of each.
    std::printf("  per algorithm, one run each (%d kinematic / %d ode episodes), episodes/s per "
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
      const auto width = std::count_if(name.begin(), name.end(), [](char ch) { return (ch & 0xC0) != 0x80; });
      name.append(static_cast<size_t>(std::max<std::ptrdiff_t>(12 - width, 0)), ' ');
      std::printf("    %s kinematic %8.0f   ode %6.0f\n", name.c_str(), 1.0 / kin_rates[i].second,
                  1.0 / ode_rates[i].second);
    }
  }
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
  run->add_option("--out", c.out_dir,
                  "Output folder. Its manifest.json and records/ (one record per finished run) "
                  "make it resumable: a folder holding this same campaign, finished, is not run "
                  "again (the report is rewritten); unfinished, it is resumed (finished runs "
                  "skipped). A folder holding another campaign is refused, naming the "
                  "differences, unless --replace; a non-empty folder holding no campaign is "
                  "refused. Ctrl-C stops cleanly (exit 130; SIGTERM 143): rerun to resume")
      ->capture_default_str();
  run->add_flag("--replace", o.replace,
                "Remove the campaign --out holds (only the files curio-lab wrote for it: "
                "records, run CSVs, summaries, plots) and run this one from scratch");
  run->add_flag("--no-journal", o.no_journal,
                "Do not journal the runs in flight (records/run-<i>.journal): a run stopped part "
                "way then starts again from its first episode");
  run->add_flag("--json", o.json, "Print the JSON summary to stdout instead of the table");
  run->add_flag("--quiet", c.quiet, "No progress lines");
  run->add_flag("--save-scenes", c.save_scenes,
                "Also write runs/<run>_scenes.csv: every episode's final ball and distractor "
                "position (training data for curio-train train --scenes)");
  int task = -1, tasks = 0;
  run->add_option("--task", task,
                  "Run only task I of --tasks N (the runs i with i mod N = I, in the campaign's "
                  "fixed order) into --out as a task folder for `merge`; recorded runs are skipped");
  run->add_option("--tasks", tasks, "How many tasks the campaign is split into (with --task)");

  auto* bench = app.add_subcommand(
      "bench", "Episodes/s per core for each physics, then the wall time of a campaign "
               "(default 3 algorithms × 15 seeds, kinematic)");
  add_common(bench);
  int ode_episodes = 2000;
  bool skip_campaign = false;
  bench->add_option("--ode-episodes", ode_episodes, "Episodes of the ODE throughput run")
      ->capture_default_str();
  bench->add_flag("--no-campaign", skip_campaign, "Only the per-core throughput");
  bool per_algorithm = false;
  bench->add_flag("--per-algorithm", per_algorithm,
                  "Also the rate of each of --algos, kinematic and ode (one run each)");

  auto* paper = app.add_subcommand(
      "paper",
      "The paper's whole figure as one campaign: RPE, RGE-EFR, MGE-EFR, RGE-VAE, MGE-VAE, "
      "RGE-βVAE, MGE-βVAE (+ the 10-module MGE-VAE-10 and MGE-βVAE-10 for the interest plots) "
      "× seeds × σ ∈ {0.05, 0.1}; learned goal spaces need the trained weight headers. "
      "Unless given, --algos is all nine, --seeds 0-14, --noise 0.05,0.1 and --out out/paper "
      "(the defaults printed below are `run`'s)");
  add_common(paper);
  paper->add_option("--out", c.out_dir, "Output folder (resumable, as for run --out)")
      ->capture_default_str();
  paper->add_flag("--replace", o.replace, "As for run --replace");
  paper->add_flag("--json", o.json, "Print the JSON summary to stdout instead of the table");
  paper->add_flag("--quiet", c.quiet, "No progress lines");
  bool efr_only = false;
  paper->add_flag("--efr-only", efr_only, "Only RPE, RGE-EFR, MGE-EFR (no trained weights needed)");

  auto* merge = app.add_subcommand(
      "merge", "Merge task folders (run --task I --tasks N) into the campaign's summary, CSVs "
               "and plots, as a local run writes them; lists missing and failed runs");
  std::vector<std::string> merge_dirs;
  std::string merge_out;
  bool allow_partial = false;
  merge->add_option("dirs", merge_dirs, "Task folders, or folders of task folders")->required();
  merge->add_option("--out", merge_out, "Output folder")->required();
  merge->add_flag("--allow-partial", allow_partial,
                  "Write the report of the runs present even if some are missing or failed");
  merge->add_flag("--json", o.json, "Print the JSON summary to stdout instead of the table");

  SlurmCli sl;
  auto add_slurm = [&](CLI::App* sub) {
    sub->add_option("--out", sl.out, "Output folder (on the shared filesystem)")->required();
    sub->add_option("--cpus", sl.resources.cpus, "CPUs per array task")->capture_default_str();
    sub->add_option("--time", sl.resources.time, "Time limit per array task (Slurm syntax)");
    sub->add_option("--partition", sl.resources.partition, "Partition (default: the cluster's)");
    sub->add_option("--job-name", sl.resources.job_name, "Job name");
    sub->add_option("--sbatch-option", sl.resources.extra,
                    "More #SBATCH lines, e.g. --sbatch-option=--account=proj (repeatable)");
    sub->add_flag("--submit", sl.submit, "Submit with sbatch and print the job ids");
  };
  auto* slurm = app.add_subcommand(
      "slurm", "Write (and --submit) a Slurm job array for a campaign: one task per chunk of "
               "runs, then a merge job; resubmitting runs only what is missing (docs/cluster.md)");
  add_common(slurm);
  add_slurm(slurm);
  sl.resources.cpus = 1;
  slurm->add_option("--chunk", sl.chunk, "Runs per array task, at most")->capture_default_str();
  slurm->add_option("--bin", sl.binary, "curio-lab as the nodes see it (default: this one)");
  auto* slurm_train = app.add_subcommand(
      "slurm-train", "Write (and --submit) a Slurm job array training one seed per task with a "
                     "resumable script (SCRIPT OUT/seed-S S); finished seeds are left out");
  add_slurm(slurm_train);
  std::string train_script, train_seeds, trainer, done_file = "4_tuned/done";
  slurm_train->add_option("--script", train_script, "e.g. host_tools/train/train_beta_vae.sh")
      ->required();
  slurm_train->add_option("--seeds", train_seeds, "Seeds: 2,3,4 or 2-4")->required();
  slurm_train->add_option("--trainer", trainer,
                          "curio-train for the script (CURIO_TRAIN; default: the one built "
                          "beside this curio-lab)");
  slurm_train->add_option("--done", done_file, "File under OUT/seed-S that marks S finished")
      ->capture_default_str();

  CLI11_PARSE(app, argc, argv);
  c.world.grasp_radius = grasp;
  c.world.distractor_noise = dnoise;
  if (run->parsed()) return tasks > 0 || task >= 0 ? cmd_run_task(o, c, task, tasks) : cmd_run(o, c);
  if (merge->parsed()) return cmd_merge(o, merge_dirs, merge_out, allow_partial);
  if (slurm->parsed()) return cmd_slurm(o, c, sl);
  if (slurm_train->parsed()) {
    if (slurm_train->get_option("--cpus")->count() == 0) sl.resources.cpus = 2;
    return cmd_slurm_train(sl, train_script, train_seeds, trainer, done_file);
  }
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
    return cmd_bench(o, c, ode_episodes, skip_campaign, per_algorithm);
  }
  return 2;
}
