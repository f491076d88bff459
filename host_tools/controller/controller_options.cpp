#include "host_tools/controller/controller_options.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "hal/linux/open_bus.hpp"
#include "host_tools/cli/bus_url_option.hpp"
#include "host_tools/cli/command_line.hpp"
#include "host_tools/cli/world_options.hpp"
#include "host_tools/journal/run_journal.hpp"

namespace curio::app::host {

void add_controller_options(CLI::App& app, ControllerCli& cli) {
  app.add_option("--bus", cli.bus_url, hal::kBusUrlHelp)
      ->check(curio::cli::bus_url_check())
      ->capture_default_str();
  app.add_option("--algo", cli.algo,
                 "RPE, RGE-EFR, MGE-EFR, or a learned goal space (RGE-βVAE, MGE-βVAE, MGE-βVAE-10, "
                 "RGE-VAE, MGE-VAE, MGE-VAE-10; needs the weight headers)")
      ->capture_default_str();
  sim::add_seed_option(&app, &cli.seed,
                       "Run seed, 0 to 2^64 - 1 (same as curio-lab --seeds N and curio-sim serve "
                       "--seed N; the arm's world must run the same seed)");
  // The world the run asks for: the arm's must be the same (camera 0x2003), or the run is
  // refused before its first episode.
  sim::add_world_params_options(&app, &cli.world.grasp_radius, &cli.world.distractor_noise);
  app.add_option("--episodes", cli.episodes, "Exploration episodes after the bootstrap")
      ->capture_default_str();
  // The exploration options, as curio-lab's (one σ): the strategy is in the journal's run
  // identity, so a resume under another one is refused naming both.
  lab::add_exploration_options(&app, &cli.exploration, lab::ExplorationSet::kOneRun);
  app.add_option("--out", cli.out_dir, "Output folder (curio-lab's files for this one run)")
      ->check(curio::cli::kOutputFolder)
      ->capture_default_str();
  app.add_flag("--image", cli.image,
               "Transfer the camera frame every episode even for engineered features (learned "
               "goal spaces always do)");
  app.add_option("--max-attempts", cli.max_attempts,
                 "Attempts per episode before giving up (1 = no retry; at most 255)")
      ->capture_default_str();
  app.add_option("--hold-time", cli.hold_time_s,
                 "Seconds the controller holds the arm after a fault (sends the joints nothing) "
                 "waiting for it to come back (nodes silent or rebooting, e.g. curio-sim serve "
                 "restarted, bus-off) before the run stops; each recovery has this long "
                 "(0.1 to 3600)")
      ->capture_default_str();
  app.add_option("--following-error", cli.following_error_urad,
                 "Largest |actual - target| position a joint may report at each period's "
                 "feedback, in microradians, before the attempt ends with following_error (the "
                 "simulated servo reaches every target: 1000; a real drive lags by its speed "
                 "times a period, docs/hil.md; 1 to 3141593)")
      ->capture_default_str();
  app.add_option("--progress-every", cli.progress_s, "Seconds between progress lines")
      ->capture_default_str();
  app.add_flag("--resume", cli.resume,
               "Continue the run journaled in --out (journal.bin): the explorer and the results "
               "so far are rebuilt by replay, then the run goes on from the episode that was in "
               "flight. Refused if the journal is another run's (seed, algorithm, σ, ...)");
  app.add_flag("--replace", cli.replace,
               "Start afresh even though --out holds a journal (it is erased)");
  app.add_flag("--no-journal", cli.no_journal, "Keep no journal (a killed run cannot be resumed)");
  app.add_option("--journal-sync-every", cli.sync_every,
                 "fdatasync the journal after every this many episodes (0: never; a SIGKILL "
                 "loses nothing either way, a power cut up to this many episodes)")
      ->capture_default_str();
  app.add_option(
         "--period-us", cli.period_us,
         "Control period on the wall clock, as on a real arm: period t of an episode starts at "
         "its first period's start + t x this many microseconds (clock_nanosleep, absolute "
         "deadlines); the lateness and the work per period go to summary.json "
         "\"control_periods\" and control_periods.png (0: periods follow as fast as the arm "
         "answers; 100 to 1000000)")
      ->check(CLI::Range(int64_t{0}, int64_t{1000000}))
      ->capture_default_str();
  app.add_option("--realtime", cli.realtime_priority,
                 "Run the control loop under SCHED_FIFO at this priority (1 to 99), memory locked "
                 "(mlockall) and the stack pre-faulted; refused with the reason when not permitted")
      ->check(CLI::Range(1, 99));
  app.add_option("--cpu", cli.cpu, "Pin the control loop to this CPU (0-based)")
      ->check(CLI::Range(0, 4095));
  app.add_option("--master-node", cli.master_node,
                 "The controller's CANopen node id (1..127): its heartbeat is COB-ID 0x700 + this, "
                 "and every joint's heartbeat consumer (0x1016) watches it")
      ->capture_default_str();
  app.add_option("--heartbeat-ms", cli.heartbeat_ms, "Period of the controller's heartbeat, ms")
      ->capture_default_str();
  app.add_option("--consumer-time-ms", cli.consumer_time_ms,
                 "How long a joint waits for the controller's heartbeat before it sends EMCY "
                 "0x8130 and stops on its quick-stop ramp (0x1016, 0x6007); above --heartbeat-ms")
      ->capture_default_str();
  app.add_option("--quick-stop-decel", cli.quick_stop_decel,
                 "The joints' quick-stop deceleration, rad/s² (0x6085)")
      ->capture_default_str();
  app.add_option("--max-joint-speed", cli.max_joint_speed,
                 "The joints' maximum speed, rad/s (0x607F, 0x6080): faster target steps are "
                 "limited by the drives")
      ->capture_default_str();
  app.add_option("--stop-timeout", cli.stop_timeout_s,
                 "Seconds a controlled stop waits for every joint's standstill before it "
                 "disables the drives anyway")
      ->capture_default_str();
  app.add_flag("--quiet", cli.quiet, "No progress lines");
  app.add_flag("--print-checksum", cli.print_checksum,
               "Print the archive's FNV-1a checksum (θ and outcome of every episode, "
               "firmware/explore/fnv1a.hpp), as the Cortex-M7 images print it");
}

std::string journal_path(const ControllerCli& cli) {
  if (cli.no_journal) return "";
  return (std::filesystem::path(cli.out_dir) / journal::host::kJournalFileName).string();
}

namespace {

// The options that are not the campaign's: one line naming the first bad one, "" if none.
std::string bus_option_problem(const ControllerCli& cli) {
  if (cli.max_attempts < 1 || cli.max_attempts > 255)
    return "--max-attempts must be 1..255 (got " + std::to_string(cli.max_attempts) + ")";
  if (!(cli.hold_time_s >= 0.1 && cli.hold_time_s <= 3600))
    return "--hold-time must be 0.1..3600 seconds";
  if (cli.following_error_urad < 1 || cli.following_error_urad > 3'141'593)
    return "--following-error must be 1..3141593 microradians (got " +
           std::to_string(cli.following_error_urad) + ")";
  if (!(cli.progress_s >= 0)) return "--progress-every must be >= 0 seconds";
  if (cli.sync_every < 0) return "--journal-sync-every must be >= 0";
  if (cli.period_us != 0 && cli.period_us < 100)
    return "--period-us must be 0 (off) or 100 to 1000000";
  if (cli.master_node < 1 || cli.master_node > 127)
    return "--master-node must be a CANopen node id 1..127 (got " +
           std::to_string(cli.master_node) + ")";
  if (cli.heartbeat_ms < 1 || cli.heartbeat_ms > 65535)
    return "--heartbeat-ms must be 1..65535 (got " + std::to_string(cli.heartbeat_ms) + ")";
  if (cli.consumer_time_ms < 1 || cli.consumer_time_ms > 65535)
    return "--consumer-time-ms must be 1..65535, the drives' 0x1016 range (got " +
           std::to_string(cli.consumer_time_ms) + ")";
  if (cli.consumer_time_ms <= cli.heartbeat_ms)
    return "--consumer-time-ms (" + std::to_string(cli.consumer_time_ms) +
           ") must be above --heartbeat-ms (" + std::to_string(cli.heartbeat_ms) +
           "): the drives would miss a heartbeat that is on time";
  if (!(cli.quick_stop_decel >= 0.001 && cli.quick_stop_decel <= 4000))
    return "--quick-stop-decel must be 0.001..4000 rad/s²";
  if (!(cli.max_joint_speed >= 0.001 && cli.max_joint_speed <= 4000))
    return "--max-joint-speed must be 0.001..4000 rad/s";
  if (!(cli.stop_timeout_s >= 0.01 && cli.stop_timeout_s <= 60))
    return "--stop-timeout must be 0.01..60 seconds";
  if (cli.resume && (cli.replace || cli.no_journal))
    return "--resume cannot be combined with --replace or --no-journal";
  return "";
}

}  // namespace

bool configure_run(const ControllerCli& cli, lab::CampaignConfig* c, BusRunOptions* options,
                   std::string* problem) {
  const auto algo = lab::find_algorithm(cli.algo);
  if (!algo) {
    std::string known;
    for (const auto& a : lab::known_algorithms()) known += (known.empty() ? "" : ", ") + a.name;
    *problem = "--algo: unknown algorithm '" + cli.algo + "' (known: " + known + ")";
    return false;
  }
  c->algorithms = {algo->name};
  c->seeds = {cli.seed};
  c->world = cli.world;
  c->episodes = cli.episodes;
  c->out_dir = cli.out_dir;
  c->quiet = cli.quiet;
  if (!lab::apply_exploration_options(cli.exploration, lab::ExplorationSet::kOneRun, c, problem))
    return false;
  *problem = bus_option_problem(cli);
  if (problem->empty()) {
    const auto problems = lab::validate_campaign(*c);
    if (!problems.empty()) *problem = problems.front();
  }
  if (!problem->empty()) return false;
  options->spec = lab::expand_runs(*c).front();
  options->controller.want_image = cli.image;
  options->controller.max_attempts = static_cast<uint8_t>(cli.max_attempts);
  options->controller.recovery_timeout_us = static_cast<uint32_t>(cli.hold_time_s * 1e6);
  options->controller.following_error_counts = static_cast<int32_t>(cli.following_error_urad);
  DriveSafetyConfig& drives = options->controller.drives;
  drives.master_node = static_cast<uint8_t>(cli.master_node);
  drives.master_heartbeat_ms = static_cast<uint16_t>(cli.heartbeat_ms);
  drives.consumer_time_ms = static_cast<uint16_t>(cli.consumer_time_ms);
  drives.quick_stop_decel = static_cast<uint32_t>(std::lround(cli.quick_stop_decel * 1e6));
  drives.max_speed = static_cast<uint32_t>(std::lround(cli.max_joint_speed * 1e6));
  options->controller.stop_timeout_us = static_cast<uint32_t>(cli.stop_timeout_s * 1e6);
  options->progress = cli.quiet ? nullptr : stderr;
  options->progress_every_s = cli.progress_s;
  options->journal_path = journal_path(cli);
  if (!cli.no_journal)
    options->bus_history_path = (std::filesystem::path(cli.out_dir) / kBusHistoryFileName).string();
  options->resume = cli.resume;
  options->journal_sync_every = static_cast<uint32_t>(cli.sync_every);
  return true;
}

}  // namespace curio::app::host
