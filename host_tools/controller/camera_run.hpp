// curio-controller with a camera on its own computer (--camera COMMAND) instead of the CAN
// camera node: the options, the camera started before the arm, every episode's frame kept
// (--save-frames), and the report of a run without ground truth.
//
// Without a camera node the arm comes up with its seven joints only (ControllerConfig::
// camera_on_bus false) and nothing tells where the ball ended: the exploration ratio cannot be
// measured during the run. The report says so and gives what is measurable from the images:
// each module's coverage of its latent box, the interest curves, the modules found controllable
// from learning progress, and the camera's own figures (frames read, the wait from the arm's
// last period to the frame taken, the frame interval). `curio-lab score` measures the ratio
// afterwards from positions supplied in a CSV (host_tools/lab/score_command.hpp).
#pragma once
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "host_tools/controller/bus_run_types.hpp"
#include "host_tools/controller/camera_command.hpp"
#include "host_tools/controller/wall_clock_pacer.hpp"
#include "host_tools/experiment/campaign_config.hpp"

namespace curio::app::host {

// curio-controller's exit status when the local camera fails during the run (it stalled,
// ended, or sent frames of another size) or does not start: the journal keeps every whole
// episode (--resume continues once the camera works).
inline constexpr int kExitCameraFailed = 4;

struct CameraCli {
  std::string camera = "can";  // "can": the CAN camera node; else a shell command
  std::string size = "64x64";
  std::string format = "raw";  // raw or ppm
  double settle_ms = 250;
  double stall_ms = 2000;
  double start_timeout_ms = 10000;
  bool save_frames = false;
};

void add_camera_options(CLI::App& app, CameraCli& cli);

// Checks the camera options against the run (a local camera needs a learned goal space) and
// sets options->controller for it. false with *problem, one line naming the option.
bool configure_camera(const CameraCli& cli, BusRunOptions* options, std::string* problem);

class CameraRun {
 public:
  // Starts the command (its stderr to out_dir/camera.log) and waits for its first frame; null
  // with *error when it does not start. The CAN camera (cli.camera "can"): null, no error.
  static std::unique_ptr<CameraRun> start(const CameraCli& cli, const std::string& out_dir,
                                          BusRunOptions* options, std::string* error);
  ~CameraRun();

  // Why the camera failed during the run (after the fault camera_failed).
  std::string failure() const {
    const std::string why = camera_.failure();
    return why.empty() ? "no fresh frame within --camera-stall + 1 s of the settle time" : why;
  }
  // Latent coverage from the finished archive (call from run_over_bus's on_finish).
  void note_archive(const Explorer& explorer);
  // The result files of a run without ground truth; returns curio-controller's exit status
  // (0, 1 when a file cannot be written, 3 when a fault may have changed the results).
  int write_report(lab::CampaignConfig campaign, const BusRunResult& result,
                   const WallClockPacer* periods, const RealtimeSettings& realtime);

 private:
  CameraRun() = default;
  std::string after_episode(const EpisodeRecord& record);

  CameraCli cli_;
  std::string out_dir_;
  CameraCommand camera_;
  std::vector<double> coverage_;  // per module
  std::FILE* latents_ = nullptr;  // latents.csv
};

// A module's coverage of its latent box [-bound, bound]^g from the archive's outcomes: the
// fraction of cells holding an outcome, 30 cells per axis for a module of one or two latents;
// for more, the mean of its latents' one-axis coverages (exposed for tests).
double latent_coverage(const Explorer& explorer, const std::vector<int>& latents, double bound);

}  // namespace curio::app::host
