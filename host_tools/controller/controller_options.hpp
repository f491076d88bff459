// curio-controller's command line: its options (add_controller_options) and what they become
// once checked (configure_run): a campaign of the one run (so the result files are curio-lab's)
// and the options of run_over_bus. A value that cannot be used is a usage error, reported as
// one line naming the option (curio::cli::usage_error, host_tools/cli/command_line.hpp).
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "host_tools/controller/bus_run.hpp"
#include "host_tools/experiment/campaign_config.hpp"
#include "host_tools/experiment/exploration_options.hpp"
#include "sim/world.hpp"

namespace curio::app::host {

struct ControllerCli {
  std::string bus_url = "udp:127.0.0.1:29500";
  std::string algo = "MGE-EFR";
  uint64_t seed = 0;
  sim::WorldParams world;  // must be the arm's (curio-sim serve's), checked at bring-up
  int episodes = 10000;
  // σ, bootstrap, D, competence, W, ε, tie rule and strategy, as curio-lab spells them.
  lab::ExplorationOptions exploration;
  std::string out_dir = "out/controller";
  bool quiet = false;
  bool image = false;
  bool print_checksum = false;
  int max_attempts = ControllerConfig{}.max_attempts;
  double hold_time_s = ControllerConfig{}.recovery_timeout_us / 1e6;
  // |actual − target| tolerated at each period's feedback, µrad (= counts).
  int64_t following_error_urad = ControllerConfig{}.following_error_counts;
  double progress_s = 2.0;
  bool resume = false;
  bool replace = false;
  bool no_journal = false;
  int sync_every = 1;
  // Wall-clock control periods (wall_clock_pacer.hpp): 0 = as fast as the arm answers.
  int64_t period_us = 0;
  int realtime_priority = 0;  // SCHED_FIFO priority, 0 = normal scheduling
  int cpu = -1;               // pin to this CPU, -1 = any
  // The drives watch the controller (docs/hil.md): its heartbeat's node id and period, the
  // drives' consumer time, the quick-stop deceleration and maximum joint speed, and how long a
  // controlled stop waits for standstill.
  int master_node = DriveSafetyConfig{}.master_node;
  int heartbeat_ms = DriveSafetyConfig{}.master_heartbeat_ms;
  int consumer_time_ms = DriveSafetyConfig{}.consumer_time_ms;
  double quick_stop_decel = DriveSafetyConfig{}.quick_stop_decel / 1e6;  // rad/s²
  double max_joint_speed = DriveSafetyConfig{}.max_speed / 1e6;          // rad/s
  double stop_timeout_s = ControllerConfig{}.stop_timeout_us / 1e6;
};

// Every option of curio-controller, bound to `cli`.
void add_controller_options(CLI::App& app, ControllerCli& cli);

// The checked options: the one run's campaign and run_over_bus's options. false with *problem,
// one line naming the option (unknown algorithm, bad --competence, a number out of range,
// contradictory flags).
bool configure_run(const ControllerCli& cli, lab::CampaignConfig* campaign, BusRunOptions* options,
                   std::string* problem);

// The journal file in --out (empty with --no-journal).
std::string journal_path(const ControllerCli& cli);

}  // namespace curio::app::host
