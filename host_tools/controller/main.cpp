// curio-controller: the firmware controller (firmware/app) on the host, driving the arm over a
// CAN bus (`curio-sim serve`, or real CiA 402 drives and a camera node), and writing the same
// result files as curio-lab for the one run.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "firmware/explore/fnv1a.hpp"
#include "hal/linux/open_bus.hpp"
#include "host_tools/controller/bus_run.hpp"
#include "host_tools/journal/run_journal.hpp"
#include "host_tools/experiment/algorithms.hpp"
#include "host_tools/experiment/campaign_config.hpp"
#include "host_tools/experiment/report.hpp"

namespace {

using namespace curio;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "curio-controller: the Curio controller (firmware/app) driving the arm over a CAN bus:\n"
      "7 CiA 402 joints + camera node, e.g. `curio-sim serve --bus URL` on the same bus.\n"
      "Runs one exploration (algorithm, seed, σ) and writes curio-lab's result files.\n"
      "Exit status: 0 done; 1 the run stopped (no arm, another master or arm on the bus, the\n"
      "arm's seed differs, the arm did not come back within --hold-time, every one of an\n"
      "episode's --max-attempts hit a fault); 2 bad option; 3 done,\n"
      "but a fault may have changed the results (marked in summary.json \"bus\"; "
      "docs/controller.md)."};
  std::string bus_url = "udp:127.0.0.1:29500";
  std::string algo = "MGE-EFR";
  int seed = 0;
  int episodes = 10000;
  int bootstrap = -1;
  double sigma = 0.05;
  double competence_clip = -1.0;
  std::string competence = "clip";
  std::string tie_rule = "latest";
  std::string out_dir = "out/controller";
  bool quiet = false;
  bool image = false;
  bool print_checksum = false;
  curio::app::ControllerConfig cc;
  int max_attempts = cc.max_attempts;
  double hold_time_s = cc.recovery_timeout_us / 1e6;
  double progress_s = 2.0;
  bool resume = false;
  bool replace = false;
  bool no_journal = false;
  int sync_every = 1;

  app.add_option("--bus", bus_url, curio::hal::kBusUrlHelp)->capture_default_str();
  app.add_option("--algo", algo,
                 "RPE, RGE-EFR, MGE-EFR, or a learned goal space (RGE-βVAE, MGE-βVAE, MGE-βVAE-10, "
                 "RGE-VAE, MGE-VAE, MGE-VAE-10; needs the weight headers)")
      ->capture_default_str();
  app.add_option("--seed", seed,
                 "Run seed (same as curio-lab --seeds N and curio-sim serve --seed N)")
      ->capture_default_str();
  app.add_option("--episodes", episodes, "Exploration episodes after the bootstrap")
      ->capture_default_str();
  app.add_option("--bootstrap", bootstrap, "Random episodes first (default: 100 EFR, 400 learned)");
  app.add_option("--noise", sigma, "Exploration noise σ on θ")->capture_default_str();
  app.add_option("--competence-clip", competence_clip,
                 "D of SPEC §2.5 (default: 1 EFR, 2 learned)");
  app.add_option("--competence", competence,
                 "How D enters the competence: clip (-min(|g-r|, D)) or scale (-|g-r|/D, the "
                 "reference code's explauto competence_dist); same as curio-lab --competence")
      ->capture_default_str();
  app.add_option(
         "--tie-rule", tie_rule,
         "Which archive entry wins a 1-NN tie: latest or earliest; same as curio-lab --tie-rule")
      ->capture_default_str();
  app.add_option("--out", out_dir, "Output folder (curio-lab's files for this one run)")
      ->capture_default_str();
  app.add_flag("--image", image,
               "Transfer the camera frame every episode even for engineered features (learned "
               "goal spaces always do)");
  app.add_option("--max-attempts", max_attempts,
                 "Attempts per episode before giving up (1 = no retry)")
      ->capture_default_str();
  app.add_option("--hold-time", hold_time_s,
                 "Seconds the controller holds the arm after a fault (sends the joints nothing) "
                 "waiting for it to come back (nodes silent or rebooting, e.g. curio-sim serve "
                 "restarted, bus-off) before the run stops; each recovery has this long")
      ->capture_default_str();
  app.add_option("--progress-every", progress_s, "Seconds between progress lines")
      ->capture_default_str();
  app.add_flag("--resume", resume,
               "Continue the run journaled in --out (journal.bin): the explorer and the results "
               "so far are rebuilt by replay, then the run goes on from the episode that was in "
               "flight. Refused if the journal is another run's (seed, algorithm, σ, ...)");
  app.add_flag("--replace", replace,
               "Start afresh even though --out holds a journal (it is erased)");
  app.add_flag("--no-journal", no_journal,
               "Keep no journal (a killed run cannot be resumed)");
  app.add_option("--journal-sync-every", sync_every,
                 "fdatasync the journal after every this many episodes (0: never; a SIGKILL "
                 "loses nothing either way, a power cut up to this many episodes)")
      ->capture_default_str();
  app.add_flag("--quiet", quiet, "No progress lines");
  app.add_flag("--print-checksum", print_checksum,
               "Print the archive's FNV-1a checksum (θ and outcome of every episode, "
               "firmware/explore/fnv1a.hpp), as the Cortex-M7 images print it");
  CLI11_PARSE(app, argc, argv);

  lab::CampaignConfig c;
  const auto spec_algo = lab::find_algorithm(algo);
  if (!spec_algo) {
    std::cerr << "curio-controller: unknown algorithm '" << algo << "'\n";
    return 2;
  }
  c.algorithms = {spec_algo->name};
  c.seeds = {seed};
  c.sigmas = {sigma};
  c.episodes = episodes;
  c.bootstrap = bootstrap;
  c.competence_clip = competence_clip;
  if (const auto m = lab::parse_competence_measure(competence)) {
    c.competence_measure = *m;
  } else {
    std::cerr << "curio-controller: unknown --competence '" << competence << "' (clip or scale)\n";
    return 2;
  }
  if (const auto t = lab::parse_tie_rule(tie_rule)) {
    c.tie_rule = *t;
  } else {
    std::cerr << "curio-controller: unknown --tie-rule '" << tie_rule << "' (latest or earliest)\n";
    return 2;
  }
  c.out_dir = out_dir;
  c.quiet = quiet;
  if (max_attempts < 1 || max_attempts > 255) {
    std::cerr << "curio-controller: --max-attempts must be 1..255\n";
    return 2;
  }
  if (!(hold_time_s >= 0.1 && hold_time_s <= 3600)) {
    std::cerr << "curio-controller: --hold-time must be 0.1..3600 seconds\n";
    return 2;
  }
  const auto problems = lab::validate_campaign(c);
  for (const auto& p : problems) std::cerr << "curio-controller: " << p << '\n';
  if (!problems.empty()) return 2;
  if (resume && (replace || no_journal)) {
    std::cerr << "curio-controller: --resume cannot be combined with --replace or --no-journal\n";
    return 2;
  }
  if (sync_every < 0) {
    std::cerr << "curio-controller: --journal-sync-every must be >= 0\n";
    return 2;
  }
  // The journal lives in --out. A used --out is resumed or replaced, never silently mixed.
  const std::string journal_path =
      (std::filesystem::path(out_dir) / journal::host::kJournalFileName).string();
  if (!no_journal) {
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (ec) {
      std::cerr << "curio-controller: cannot create --out " << out_dir << ": " << ec.message()
                << '\n';
      return 1;
    }
    // A file that holds no journal (erased: a run that stopped before its first episode, e.g.
    // with no arm on the bus) has nothing to lose and does not block a new run.
    if (!resume && !replace && std::filesystem::exists(journal_path)) {
      std::string why;
      const auto j = journal::host::RunJournal::open(journal_path, &why);
      if (!j || j->has_journal()) {
        std::cerr << "curio-controller: " << journal_path << " holds a journal ("
                  << (j ? journal::host::describe(j->scan()) : why)
                  << "); continue it with --resume, or start over with --replace\n";
        return 2;
      }
    }
  }

  std::string error;
  auto bus = hal::open_bus(bus_url, &error);
  if (!bus) {
    std::cerr << "curio-controller: cannot open bus '" << bus_url << "': " << error << '\n';
    return 1;
  }
  app::host::BusRunOptions options;
  options.spec = lab::expand_runs(c).front();
  options.controller = cc;
  options.controller.want_image = image;
  options.controller.max_attempts = static_cast<uint8_t>(max_attempts);
  options.controller.recovery_timeout_us = static_cast<uint32_t>(hold_time_s * 1e6);
  options.progress = quiet ? nullptr : stderr;
  options.progress_every_s = progress_s;
  if (!no_journal) {
    options.journal_path = journal_path;
    options.bus_history_path =
        (std::filesystem::path(out_dir) / app::host::kBusHistoryFileName).string();
  }
  options.resume = resume;
  options.journal_sync_every = static_cast<uint32_t>(sync_every);
  if (!quiet)
    std::fprintf(stderr, "curio-controller: %s seed %d σ %g, %d + %d episodes over %s\n",
                 options.spec.algorithm.name.c_str(), seed, sigma,
                 options.spec.explorer.n_bootstrap, options.spec.explorer.n_episodes,
                 bus_url.c_str());
  uint32_t archive_checksum = 0;
  int archived = 0;
  const app::host::BusRunResult result =
      app::host::run_over_bus(bus.get(), options, [&](const Explorer& explorer) {
        Fnv1a f;
        f.add_archive(explorer.archive());
        archive_checksum = f.h;
        archived = explorer.archive().size();
      });
  const lab::RunResult& r = result.run;
  const int done = static_cast<int>(r.final_ball.size());
  // Rates over the episodes this process ran (not those replayed from the journal).
  const int ran = done - result.resumed_episodes;
  std::fprintf(stderr,
               "curio-controller: %d episodes (%d replayed from the journal) in %.1f s "
               "(%.0f episodes/s), %.0f frames/episode sent + %.0f received; faults: %s\n",
               done, result.resumed_episodes, result.seconds,
               result.seconds > 0 ? ran / result.seconds : 0.0,
               ran > 0 ? static_cast<double>(result.frames_sent) / ran : 0.0,
               ran > 0 ? static_cast<double>(result.frames_received) / ran : 0.0,
               app::host::fault_summary(result.counters).c_str());
  if (!r.error.empty()) {
    std::cerr << "curio-controller: run stopped: " << r.error << '\n';
    return 1;
  }
  if (print_checksum)
    std::printf("archive checksum 0x%08x (%d episodes)\n", static_cast<unsigned>(archive_checksum),
                archived);
  c.physics = r.spec.physics;
  const std::vector<lab::RunResult> results = {r};
  auto summary = lab::summarize_campaign(c, results, result.seconds);
  // What the bus did to this run: faults, replays, node reboots, and whether the results are
  // those of an undisturbed run (summary.json "bus"; summary.md gets the lines of "notes").
  // Over every process of the run (a resumed run's earlier ones from bus_counters.json).
  const app::host::BusHistory& k = result.history;
  nlohmann::json faults = nlohmann::json::object();
  for (size_t i = 1; i < app::kFaultKinds; ++i)
    if (k.faults[i] > 0) faults[app::to_string(static_cast<app::Fault>(i))] = k.faults[i];
  summary["bus"] = {{"faults", faults},
                    {"fault_total", k.fault_total},
                    {"replays", k.replays},
                    {"capture_retries", k.capture_retries},
                    {"node_reboots", k.node_reboots},
                    {"controller_processes", k.processes},
                    {"episode_indexed_scenes", result.episode_indexed},
                    {"results", result.inexact.empty() ? "exact" : "may differ"}};
  if (!result.inexact.empty()) summary["bus"]["why"] = result.inexact;
  char note[512];
  std::snprintf(note, sizeof note,
                "Over the bus: %llu faults, %llu replayed attempts, %llu capture retries, %llu "
                "node reboots; results: %s.",
                static_cast<unsigned long long>(k.fault_total),
                static_cast<unsigned long long>(k.replays),
                static_cast<unsigned long long>(k.capture_retries),
                static_cast<unsigned long long>(k.node_reboots),
                result.inexact.empty()
                    ? (k.fault_total > 0 ? "those of an undisturbed run (episode-indexed scenes)"
                                         : "those of an undisturbed run")
                    : ("MAY DIFFER from an undisturbed run: " + result.inexact).c_str());
  summary["notes"] = {note};
  std::vector<std::string> warnings;
  if (!lab::write_report(c, results, summary, &warnings, &error)) {
    std::cerr << "curio-controller: " << error << '\n';
    return 1;
  }
  for (const auto& w : warnings) std::cerr << "curio-controller: warning: " << w << '\n';
  std::printf("exploration ratio after %d episodes: %.4f (%d grasps); results in %s/\n", done,
              r.ratio.empty() ? 0.0 : r.ratio.back(), r.grasps.empty() ? 0 : r.grasps.back(),
              out_dir.c_str());
  if (k.fault_total > 0 || k.node_reboots > 0) std::fprintf(stderr, "curio-controller: %s\n", note);
  // Controllable-feature discovery (host_tools/experiment/controllability.hpp) from this run's
  // learning progress, beside the ground truth when the goal space has one.
  if (!r.verdicts.empty()) {
    const std::string truth = lab::expected_verdict(r);
    std::printf("controllable (from learning progress alone): {%s}", lab::verdict_text(r).c_str());
    if (!truth.empty())
      std::printf("; the ball's %s: {%s}", truth == "ball" ? "module" : "latents", truth.c_str());
    std::printf("\n");
  }
  if (!result.inexact.empty()) {
    std::fprintf(stderr,
                 "curio-controller: results written but marked (summary.json \"bus\"): a fault "
                 "may have changed them; exit status 3\n");
    return 3;
  }
  return 0;
}
