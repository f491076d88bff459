// curio-controller: the firmware controller (firmware/app) on the host, driving the arm over a
// CAN bus (`curio-sim serve`, or real CiA 402 drives and a camera node), and writing the same
// result files as curio-lab for the one run.
//
// Exit status: 0 done; 1 the run stopped, or a result file cannot be written; 2 a usage error
// (one line naming the option); 3 done, but a fault may have changed the results; 130/143
// killed by SIGINT/SIGTERM (the journal in --out resumes the run: --resume).
#include <cstdio>
#include <memory>

#include <CLI/CLI.hpp>

#include "firmware/explore/fnv1a.hpp"
#include "hal/linux/open_bus.hpp"
#include "host_tools/common/output_folder.hpp"
#include "host_tools/controller/bus_journal.hpp"
#include "host_tools/controller/bus_report.hpp"
#include "host_tools/controller/bus_run.hpp"
#include "host_tools/controller/camera_run.hpp"
#include "host_tools/controller/controller_options.hpp"
#include "host_tools/controller/wall_clock_pacer.hpp"
#include "sim/cli/command_line.hpp"

namespace {

constexpr const char* kAbout =
    "curio-controller: the Curio controller (firmware/app) driving the arm over a CAN bus:\n"
    "7 CiA 402 joints + camera node, e.g. `curio-sim serve --bus URL` on the same bus.\n"
    "Runs one exploration (algorithm, seed, σ) and writes curio-lab's result files.\n"
    "Exit status: 0 done; 1 the run stopped (no arm, another master or arm on the bus, the\n"
    "arm's seed differs, the arm did not come back within --hold-time, every one of an\n"
    "episode's --max-attempts hit a fault); 2 bad option; 3 done,\n"
    "but a fault may have changed the results (marked in summary.json \"bus\"; "
    "docs/controller.md); 4 the --camera command did not start, stalled, ended or sent\n"
    "frames of another size (the journal keeps every whole episode).";

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
    std::fprintf(stderr, "curio-controller: %s seed %llu σ %g, %d + %d episodes over %s\n",
                 options.spec.algorithm.name.c_str(),
                 static_cast<unsigned long long>(cli.seed), cli.sigma,
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
  if (!result.run.error.empty()) {
    std::fprintf(stderr, "curio-controller: run stopped: %s\n", result.run.error.c_str());
    if (camera && result.counters.faults[static_cast<size_t>(app::Fault::kCameraFailed)] > 0) {
      std::fprintf(stderr, "curio-controller: the camera failed: %s; the journal keeps every "
                   "whole episode (--resume)\n", camera->failure().c_str());
      return app::host::kExitCameraFailed;
    }
    return cli::kRuntimeFailure;
  }
  if (cli.print_checksum)
    std::printf("archive checksum 0x%08x (%d episodes)\n", static_cast<unsigned>(archive_checksum),
                archived);
  if (camera) return camera->write_report(campaign, result, pacer.get(), realtime);
  return app::host::write_bus_report(campaign, result, pacer.get(), realtime);
}
