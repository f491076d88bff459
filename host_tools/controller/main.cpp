// curio-controller: the firmware controller (firmware/app) on the host, driving the arm over a
// CAN bus (`curio-sim serve`, or real CiA 402 drives and a camera node), and writing the same
// result files as curio-lab for the one run.
//
// Every end of a run that reached the arm is a controlled stop (firmware/app/controlled_stop.hpp):
// quick stop, standstill, disable; one line says how it went.
//
// Exit status: 0 done; 1 the run stopped (a fault, no arm, another master), or a result file
// cannot be written; 2 a usage error (one line naming the option); 3 done, but a fault may have
// changed the results; 129/130/143 stopped by SIGHUP/SIGINT/SIGTERM after a controlled stop
// (the journal in --out resumes the run: --resume).
#include <csignal>
#include <cstdio>
#include <memory>
#include <type_traits>

#include <CLI/CLI.hpp>

#include "firmware/explore/fnv1a.hpp"
#include "hal/linux/open_bus.hpp"
#include "host_tools/cli/command_line.hpp"
#include "host_tools/common/output_folder.hpp"
#include "host_tools/controller/bus_journal.hpp"
#include "host_tools/controller/bus_report.hpp"
#include "host_tools/controller/bus_run.hpp"
#include "host_tools/controller/camera_run.hpp"
#include "host_tools/controller/fault_text.hpp"
#include "host_tools/controller/controller_options.hpp"
#include "host_tools/controller/wall_clock_pacer.hpp"

namespace {

constexpr const char* kAbout =
    "curio-controller: the Curio controller (firmware/app) driving the arm over a CAN bus:\n"
    "7 CiA 402 joints + camera node, e.g. `curio-sim serve --bus URL` on the same bus.\n"
    "Runs one exploration (algorithm, seed, σ) and writes curio-lab's result files.\n"
    "Exit status: 0 done; 1 the run stopped (no arm, another master or arm on the bus, the\n"
    "arm's seed differs, the arm did not come back within --hold-time, every one of an\n"
    "episode's --max-attempts hit a fault, a drive refused its configuration); 2 bad option;\n"
    "3 done, but a fault may have changed the results (marked in summary.json \"bus\";\n"
    "docs/controller.md); 4 the --camera command did not start, stalled, ended or sent\n"
    "frames of another size (the journal keeps every whole episode); 129/130/143 stopped by\n"
    "SIGHUP/SIGINT/SIGTERM. Every end is a controlled stop of the arm: quick stop,\n"
    "standstill, disable (docs/hil.md).";

// The signal that asked the run to stop (0: none). The handler only stores it; the
// controller's pump sees it within 10 ms and the run ends with a controlled stop.
volatile std::sig_atomic_t g_stop_signal = 0;
static_assert(std::is_same_v<std::sig_atomic_t, int>, "the controller reads it as an int");

extern "C" void on_stop_signal(int signo) { g_stop_signal = signo; }

void install_stop_signals() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a blocking wait returns at once
  for (int signo : {SIGTERM, SIGINT, SIGHUP}) sigaction(signo, &sa, nullptr);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace curio;
  CLI::App app{kAbout, "curio-controller"};
  app::host::ControllerCli cli;
  app::host::add_controller_options(app, cli);
  app::host::CameraCli camera_cli;
  app::host::add_camera_options(app, camera_cli);
  if (const auto code = cli::parse(app, argc, argv)) return *code;
  lab::CampaignConfig campaign;
  app::host::BusRunOptions options;
  std::string message;
  if (!app::host::configure_run(cli, &campaign, &options, &message) ||
      !app::host::configure_camera(camera_cli, &options, &message))
    return cli::usage_error(app, message);
  // One writer per --out, proved writable before the first episode (with --no-journal too).
  const auto claim = host::claim_output_folder_or_say("curio-controller", cli.out_dir,
                                                      host::OutputAccess::kExclusive);
  if (!claim) return cli::kRuntimeFailure;
  // The journal lives in --out. A used --out is resumed or replaced, never silently mixed.
  if (!cli.no_journal) {
    const auto folder = app::host::prepare_out_folder(cli.out_dir, options.journal_path, cli.resume,
                                                      cli.replace, &message);
    if (folder == app::host::OutFolder::kHoldsJournal) return cli::usage_error(app, message);
    if (folder == app::host::OutFolder::kCannotCreate) {
      std::fprintf(stderr, "curio-controller: %s\n", message.c_str());
      return cli::kRuntimeFailure;
    }
  }
  auto bus = hal::open_bus(cli.bus_url, &message);
  if (!bus) {
    std::fprintf(stderr, "curio-controller: cannot open bus '%s': %s\n", cli.bus_url.c_str(),
                 message.c_str());
    return cli::kRuntimeFailure;
  }
  if (!cli.quiet)
    std::fprintf(stderr, "curio-controller: %s%s seed %llu σ %g, %d + %d episodes over %s\n",
                 options.spec.algorithm.name.c_str(),
                 campaign.explore == "spec" ? "" : (" (explore " + campaign.explore + ")").c_str(),
                 static_cast<unsigned long long>(cli.seed), campaign.sigmas.front(),
                 options.spec.explorer.n_bootstrap, options.spec.explorer.n_episodes,
                 cli.bus_url.c_str());
  // Wall-clock periods and real-time scheduling (wall_clock_pacer.hpp), set before the arm moves.
  const app::host::RealtimeSettings realtime{cli.realtime_priority, cli.cpu};
  if (const std::string why = app::host::enable_realtime(realtime); !why.empty()) {
    std::fprintf(stderr, "curio-controller: %s\n", why.c_str());
    return cli::kRuntimeFailure;
  }
  // A camera on this computer: started, and its first frame in, before the arm moves.
  const auto camera = app::host::CameraRun::start(camera_cli, cli.out_dir, &options, &message);
  if (!camera && !message.empty()) {
    std::fprintf(stderr, "curio-controller: %s\n", message.c_str());
    return app::host::kExitCameraFailed;
  }
  std::unique_ptr<app::host::WallClockPacer> pacer;
  if (cli.period_us > 0) {
    pacer = std::make_unique<app::host::WallClockPacer>(
        cli.period_us, static_cast<int64_t>(options.spec.explorer.n_bootstrap + options.spec.explorer.n_episodes) *
                           kStepsPerEpisode);
    options.pacer = pacer.get();
  }
  install_stop_signals();
  options.stop_signal = &g_stop_signal;
  uint32_t archive_checksum = 0;
  int archived = 0;
  const auto result = app::host::run_over_bus(bus.get(), options, [&](const Explorer& explorer) {
    Fnv1a f;
    f.add_archive(explorer.archive());
    archive_checksum = f.h;
    archived = explorer.archive().size();
    if (camera) camera->note_archive(explorer);
  });
  app::host::print_bus_run(result);
  if (result.stopped)
    std::fprintf(stderr, "curio-controller: %s\n", app::host::stop_report_text(result.stop).c_str());
  const int archived_now = static_cast<int>(result.run.final_ball.size());
  const bool resumable = !cli.no_journal && archived_now > 0;
  if (result.stop_signal != 0) {
    std::fprintf(stderr, "curio-controller: stopped by %s after %d whole episodes%s\n",
                 app::host::signal_name(result.stop_signal).c_str(), archived_now,
                 resumable ? " (journal in --out): resume with --resume" : "");
    return 128 + result.stop_signal;
  }
  if (!result.run.error.empty()) {
    std::fprintf(stderr, "curio-controller: run stopped: %s\n", result.run.error.c_str());
    if (camera && result.counters.faults[static_cast<size_t>(app::Fault::kCameraFailed)] > 0) {
      std::fprintf(stderr, "curio-controller: the camera failed: %s; the journal keeps every "
                   "whole episode (--resume)\n", camera->failure().c_str());
      return app::host::kExitCameraFailed;
    }
    if (resumable && result.run.error.find("--resume") == std::string::npos)
      std::fprintf(stderr,
                   "curio-controller: the journal in --out keeps %d whole episodes: resume with "
                   "--resume once the cause is fixed\n",
                   archived_now);
    return cli::kRuntimeFailure;
  }
  if (cli.print_checksum)
    std::printf("archive checksum 0x%08x (%d episodes)\n", static_cast<unsigned>(archive_checksum),
                archived);
  if (camera) return camera->write_report(campaign, result, pacer.get(), realtime);
  return app::host::write_bus_report(campaign, result, pacer.get(), realtime);
}
