#include "host_tools/controller/camera_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/controller/fault_text.hpp"
#include "host_tools/experiment/report.hpp"
#include "sim/render.hpp"

namespace curio::app::host {

namespace fs = std::filesystem;

namespace {

constexpr const char* kNotMeasured =
    "not measured: a camera on the controller's computer gives no ground truth (no camera node "
    "on the bus, no tracker); score the run afterwards with `curio-lab score --run DIR "
    "--positions CSV` (episode, ball x, ball y per line, from any tracker)";

// p in [0, 1] of `v` (nearest rank); 0 when empty.
double quantile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<size_t>(std::ceil(p * static_cast<double>(v.size())));
  return v[i == 0 ? 0 : std::min(i, v.size()) - 1];
}

nlohmann::json spread(const std::vector<double>& v) {
  return {{"p50", quantile(v, 0.5)}, {"p99", quantile(v, 0.99)}, {"max", quantile(v, 1.0)}};
}

}  // namespace

void add_camera_options(CLI::App& app, CameraCli& cli) {
  app.add_option("--camera", cli.camera,
                 "Where the camera frame comes from: can (the CAN camera node 32, with the ground "
                 "truth), or a shell command on this computer whose standard output is raw RGB24 "
                 "frames of --camera-size, e.g. 'ffmpeg -f v4l2 -i /dev/video0 -vf scale=64:64 -f "
                 "rawvideo -pix_fmt rgb24 -' (docs/hil.md, \"A camera on the controller's "
                 "computer\"). A command: the arm comes up without node 32, learned goal spaces "
                 "only, no exploration ratio during the run")
      ->capture_default_str();
  app.add_option("--camera-size", cli.size,
                 "WIDTHxHEIGHT of the command's frames (resampled to 64x64 as curio-encode "
                 "--resize does; 1 to 4096 each)")
      ->capture_default_str();
  app.add_option("--camera-format", cli.format,
                 "raw: headerless RGB24 frames (ffmpeg -f rawvideo -pix_fmt rgb24 -), a frame of "
                 "another size noticed only when the stream ends mid-frame; ppm: a PPM (P6) stream "
                 "(ffmpeg -f image2pipe -c:v ppm -), every frame's size checked against "
                 "--camera-size")
      ->capture_default_str();
  app.add_option("--settle-ms", cli.settle_ms,
                 "The frame taken is the first that arrived this many milliseconds or more after "
                 "the episode's last control period (the arm settled; 0 to 10000)")
      ->check(CLI::Range(0.0, 10000.0))
      ->capture_default_str();
  app.add_option("--camera-stall", cli.stall_ms,
                 "Milliseconds without a frame after which the camera counts as stalled and the "
                 "run stops (exit 4; 50 to 600000)")
      ->check(CLI::Range(50.0, 600000.0))
      ->capture_default_str();
  app.add_option("--camera-start-timeout", cli.start_timeout_ms,
                 "Milliseconds the command has for its first whole frame (100 to 600000)")
      ->check(CLI::Range(100.0, 600000.0))
      ->capture_default_str();
  app.add_flag("--save-frames", cli.save_frames,
               "Keep every episode's frame as the camera sent it: --out/frames/episode_NNNNNN.png "
               "(a tracker can score the run later: curio-lab score)");
}

bool configure_camera(const CameraCli& cli, BusRunOptions* options, std::string* problem) {
  if (cli.camera == "can") {
    if (cli.save_frames) *problem = "--save-frames needs --camera COMMAND (a local camera)";
    return problem->empty();
  }
  if (cli.camera.empty()) {
    *problem = "--camera: empty (can, or a command that prints raw RGB24 frames)";
    return false;
  }
  int w = 0, h = 0;
  if (!parse_frame_size(cli.size, &w, &h)) {
    *problem = "--camera-size: '" + cli.size + "' is not WIDTHxHEIGHT with 1 to 4096 each";
    return false;
  }
  if (cli.format != "raw" && cli.format != "ppm") {
    *problem = "--camera-format: '" + cli.format + "' (raw or ppm)";
    return false;
  }
  if (!(cli.settle_ms >= 0 && cli.settle_ms <= 10000)) {
    *problem = "--settle-ms must be 0..10000";
    return false;
  }
  if (!(cli.stall_ms >= 50 && cli.stall_ms <= 600000)) {
    *problem = "--camera-stall must be 50..600000 milliseconds";
    return false;
  }
  if (!(cli.start_timeout_ms >= 100 && cli.start_timeout_ms <= 600000)) {
    *problem = "--camera-start-timeout must be 100..600000 milliseconds";
    return false;
  }
  const lab::AlgorithmSpec& algo = options->spec.algorithm;
  if (algo.outcome != lab::OutcomeSource::kLatents) {
    *problem = "--camera: " + algo.name +
               " needs the ball and distractor positions (ground truth), which only a camera "
               "node on the bus gives; with a camera on this computer use a learned goal space "
               "(MGE-βVAE, RGE-βVAE, MGE-VAE, ...)";
    return false;
  }
  ControllerConfig& c = options->controller;
  c.camera_on_bus = false;
  c.frame_settle_us = static_cast<uint32_t>(cli.settle_ms * 1000);
  // The source names a stall first; this bounds a capture whatever the source does.
  c.frame_timeout_us = static_cast<uint32_t>(cli.stall_ms * 1000) + 1'000'000;
  return true;
}

std::unique_ptr<CameraRun> CameraRun::start(const CameraCli& cli, const std::string& out_dir,
                                            BusRunOptions* options, std::string* error) {
  if (cli.camera == "can") return nullptr;
  std::unique_ptr<CameraRun> run(new CameraRun);
  run->cli_ = cli;
  run->out_dir_ = out_dir;
  CameraCommandOptions o;
  o.command = cli.camera;
  parse_frame_size(cli.size, &o.width, &o.height);
  o.ppm = cli.format == "ppm";
  o.stall_ms = static_cast<uint32_t>(cli.stall_ms);
  o.start_timeout_ms = static_cast<uint32_t>(cli.start_timeout_ms);
  o.log_path = (fs::path(out_dir) / "camera.log").string();
  if (cli.save_frames) {
    std::error_code ec;
    fs::create_directories(fs::path(out_dir) / "frames", ec);
    if (ec) {
      *error = "cannot create " + (fs::path(out_dir) / "frames").string() + ": " + ec.message();
      return nullptr;
    }
  }
  if (std::string why = run->camera_.start(o); !why.empty()) {
    *error = "the camera did not start: " + why;
    return nullptr;
  }
  options->frame_source = &run->camera_;
  CameraRun* self = run.get();
  options->after_episode = [self](const EpisodeRecord& r) { return self->after_episode(r); };
  return run;
}

CameraRun::~CameraRun() {
  camera_.stop();
  if (latents_ != nullptr) std::fclose(latents_);
}

std::string CameraRun::after_episode(const EpisodeRecord& record) {
  // latents.csv: where each episode's frame lies in the goal space (μ of the encoder).
  const std::string latents = (fs::path(out_dir_) / "latents.csv").string();
  if (latents_ == nullptr) {
    const bool fresh = !fs::exists(latents);
    latents_ = std::fopen(latents.c_str(), "a");
    if (latents_ == nullptr) return "cannot write " + latents;
    if (fresh) {
      std::fprintf(latents_, "episode");
      for (int i = 0; i < record.outcome_dim; ++i) std::fprintf(latents_, ",z%d", i);
      std::fprintf(latents_, "\n");
    }
  }
  std::fprintf(latents_, "%d", record.episode);
  for (int i = 0; i < record.outcome_dim; ++i) std::fprintf(latents_, ",%.9g", record.outcome[i]);
  std::fprintf(latents_, "\n");
  if (std::fflush(latents_) != 0) return "cannot write " + latents;
  if (!cli_.save_frames) return "";
  const CameraCommandOptions& o = camera_.options();
  const std::vector<uint8_t>& bytes = camera_.last_taken();
  std::vector<float> hwc(bytes.size());
  for (size_t i = 0; i < bytes.size(); ++i) hwc[i] = static_cast<float>(bytes[i]) / 255.0f;
  char name[48];
  std::snprintf(name, sizeof name, "episode_%06d.png", record.episode);
  const std::string path = (fs::path(out_dir_) / "frames" / name).string();
  std::string why;
  if (!sim::write_png(path, hwc.data(), o.width, o.height, &why)) return "--save-frames: " + why;
  return "";
}

double latent_coverage(const Explorer& explorer, const std::vector<int>& latents, double bound) {
  const Archive& a = explorer.archive();
  constexpr int kCells = 30;
  const auto cell = [&](float v) {
    if (!(v >= -bound && v <= bound)) return -1;
    const int c = static_cast<int>((v + bound) / (2 * bound) * kCells);
    return c >= kCells ? kCells - 1 : c;
  };
  if (latents.empty() || a.size() == 0) return 0.0;
  if (latents.size() <= 2) {
    std::set<int> hit;
    for (int i = 0; i < a.size(); ++i) {
      int index = 0;
      bool inside = true;
      for (int d : latents) {
        const int c = cell(a.outcome(i, d));
        inside = inside && c >= 0;
        index = index * kCells + c;
      }
      if (inside) hit.insert(index);
    }
    return static_cast<double>(hit.size()) / std::pow(kCells, static_cast<double>(latents.size()));
  }
  double sum = 0.0;
  for (int d : latents) sum += latent_coverage(explorer, {d}, bound);
  return sum / static_cast<double>(latents.size());
}

void CameraRun::note_archive(const Explorer& explorer) {
  coverage_.clear();
  const ExplorerConfig& c = explorer.config();
  for (int m = 0; m < c.n_modules; ++m) {
    std::vector<int> dims;
    for (int k = 0; k < c.modules[m].n_dims; ++k) dims.push_back(c.modules[m].dims[k]);
    coverage_.push_back(latent_coverage(explorer, dims, c.goal_bound));
  }
}

int CameraRun::write_report(lab::CampaignConfig campaign, const BusRunResult& result,
                            const WallClockPacer* periods, const RealtimeSettings& realtime) {
  const lab::RunResult& r = result.run;
  campaign.physics = r.spec.physics;
  const std::vector<lab::RunResult> results = {r};
  // curio-lab's files, then those that need the ground truth removed: what is left is the
  // interest (runs/*_interest.csv, interest_*.png) and controllability.csv.
  nlohmann::json summary = lab::summarize_campaign(campaign, results, result.seconds);
  std::vector<std::string> warnings, written;
  std::string error;
  if (!lab::write_report(campaign, results, summary, &warnings, &error, &written)) {
    std::fprintf(stderr, "curio-controller: %s\n", error.c_str());
    return 1;
  }
  const std::string stem = lab::run_stem(r.spec);
  for (const std::string& f : written) {
    const std::string name = fs::path(f).filename().string();
    const bool needs_truth = name == stem + ".csv" || name == "summary.csv" ||
                             name.rfind("ratio_", 0) == 0 || name.rfind("ball_positions_", 0) == 0;
    std::error_code ec;
    if (needs_truth) fs::remove(f, ec);
  }
  // summary.json / summary.md of a run without ground truth.
  const CameraStats s = camera_.stats();
  bool fresh = true;
  for (size_t i = 0; i < s.sequence.size(); ++i) {
    if (i > 0 && s.sequence[i] <= s.sequence[i - 1]) fresh = false;
    if (s.wait_ms[i] < s.settle_ms) fresh = false;
  }
  nlohmann::json modules = nlohmann::json::array();
  for (size_t m = 0; m < coverage_.size(); ++m) {
    nlohmann::json j = {{"module", m < r.module_names.size() ? r.module_names[m] : std::to_string(m)},
                        {"latent_coverage", coverage_[m]},
                        {"chosen", m < r.module_choices.size() ? r.module_choices[m] : 0}};
    if (m < r.verdicts.size()) {
      j["controllable"] = r.verdicts[m].controllable;
      j["mean_progress"] = r.verdicts[m].mean_progress;
      j["relative_interest"] = r.verdicts[m].relative_interest;
    }
    if (!r.interest.empty() && m < r.interest.back().size()) j["final_interest"] = r.interest.back()[m];
    modules.push_back(j);
  }
  nlohmann::json out = {
      {"algorithm", r.spec.algorithm.name},
      {"seed", r.spec.explorer.seed},
      {"sigma", r.spec.explorer.sigma},
      {"episodes", r.final_ball.size()},
      {"ground_truth", false},
      {"exploration_ratio", nullptr},
      {"exploration_ratio_why", kNotMeasured},
      {"modules", modules},
      {"controllable", r.verdicts.empty() ? "" : lab::verdict_text(r)},
      {"camera",
       {{"command", cli_.camera},
        {"size", cli_.size},
        {"settle_ms", cli_.settle_ms},
        {"frames_read", s.frames_read},
        {"frames_taken", s.frames_taken},
        {"frames_superseded", s.frames_superseded},
        {"frames_distrusted", s.frames_distrusted},
        {"every_frame_fresh", fresh},
        {"first_sequence", s.sequence.empty() ? 0 : s.sequence.front()},
        {"last_sequence", s.sequence.empty() ? 0 : s.sequence.back()},
        {"wait_ms", spread(s.wait_ms)},
        {"age_ms", spread(s.age_ms)},
        {"frame_interval_ms", spread(s.gap_ms)}}},
      {"bus",
       {{"fault_total", result.history.fault_total},
        {"replays", result.history.replays},
        {"faults", fault_summary(result.counters)}}},
      {"seconds", result.seconds}};
  if (periods != nullptr) out["control_periods"] = period_stats_json(*periods, realtime);
  std::ostringstream md;
  md << "# " << r.spec.algorithm.name << " seed " << r.spec.explorer.seed << ", "
     << r.final_ball.size() << " episodes, camera on the controller's computer\n\n"
     << "Exploration ratio: " << kNotMeasured << ".\n\n"
     << "| module | latent coverage | chosen | controllable |\n|---|---|---|---|\n";
  for (const auto& m : modules)
    md << "| " << m["module"].get<std::string>() << " | " << m["latent_coverage"].get<double>()
       << " | " << m["chosen"].get<int>() << " | "
       << (m.contains("controllable") ? (m["controllable"].get<bool>() ? "yes" : "no") : "-")
       << " |\n";
  md << "\nCamera: " << s.frames_read << " frames read, " << s.frames_taken
     << " taken (every one fresh: " << (fresh ? "yes" : "NO") << "), from the last period to the "
     << "frame p50 " << quantile(s.wait_ms, 0.5) << " ms, max " << quantile(s.wait_ms, 1.0)
     << " ms; frame interval p50 " << quantile(s.gap_ms, 0.5) << " ms.\n";
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"summary.json", out.dump(2) + "\n"},
                                   {"summary.md", md.str()}}) {
    if (!curio::host::write_file_atomically((fs::path(campaign.out_dir) / name).string(), text, &error)) {
      std::fprintf(stderr, "curio-controller: %s\n", error.c_str());
      return 1;
    }
  }
  if (periods != nullptr) {
    bool gnuplot_missing = false;
    const std::string why = write_period_files(*periods, campaign.out_dir, &gnuplot_missing);
    if (!why.empty() && !gnuplot_missing) {
      std::fprintf(stderr, "curio-controller: %s\n", why.c_str());
      return 1;
    }
  }
  for (const auto& w : warnings) std::fprintf(stderr, "curio-controller: warning: %s\n", w.c_str());
  std::printf("exploration ratio after %zu episodes: not measured (no ground truth with a camera "
              "on this computer; curio-lab score measures it from positions); results in %s/\n",
              r.final_ball.size(), campaign.out_dir.c_str());
  for (size_t m = 0; m < coverage_.size(); ++m)
    std::printf("module %s: latent coverage %.4f\n",
                m < r.module_names.size() ? r.module_names[m].c_str() : "?", coverage_[m]);
  std::printf("camera: %llu frames read, %llu taken, every one fresh: %s; last period to frame p50 "
              "%.1f ms, max %.1f ms\n",
              static_cast<unsigned long long>(s.frames_read),
              static_cast<unsigned long long>(s.frames_taken), fresh ? "yes" : "NO",
              quantile(s.wait_ms, 0.5), quantile(s.wait_ms, 1.0));
  if (!r.verdicts.empty())
    std::printf("controllable (from learning progress alone): {%s}\n", lab::verdict_text(r).c_str());
  return result.inexact.empty() ? 0 : 3;
}

}  // namespace curio::app::host
