#include "sim/cli/serve_command.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>

#include "hal/linux/open_bus.hpp"
#include "host_tools/cli/bus_url_option.hpp"
#include "host_tools/cli/command_line.hpp"
#include "host_tools/cli/world_options.hpp"
#include "sim/serve/arm_nodes.hpp"
#include "sim/serve/camera_stream.hpp"

namespace curio::sim {
namespace {

std::atomic<int> g_signal{0};  // the signal that stopped the serve (0: none yet)
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

extern "C" void on_signal(int sig) {
  g_signal.store(sig);
}

void print_counters(std::FILE* err, const serve::ServeCounters& c, double seconds) {
  std::fprintf(
      err,
      "curio-sim serve: %.1f s: %llu episodes (%llu replayed), %llu steps, %llu captures, "
      "%llu images; frames in %llu out %llu; foreign %llu, malformed %llu, "
      "clamped targets %llu, limited steps %llu, EMCY %llu, missed heartbeats %llu, "
      "ramp steps %llu, tx failures %llu\n",
      seconds, static_cast<unsigned long long>(c.episodes),
      static_cast<unsigned long long>(c.replays), static_cast<unsigned long long>(c.steps),
      static_cast<unsigned long long>(c.captures), static_cast<unsigned long long>(c.images_sent),
      static_cast<unsigned long long>(c.frames_in), static_cast<unsigned long long>(c.frames_out),
      static_cast<unsigned long long>(c.foreign), static_cast<unsigned long long>(c.malformed),
      static_cast<unsigned long long>(c.rejected_targets),
      static_cast<unsigned long long>(c.limited_targets),
      static_cast<unsigned long long>(c.emcy_sent),
      static_cast<unsigned long long>(c.heartbeats_missed),
      static_cast<unsigned long long>(c.ramp_steps), static_cast<unsigned long long>(c.tx_failures));
}

// The drives' view of the controller's clock (--period-us).
void print_sync_timing(std::FILE* err, const serve::SyncTiming::Summary& t) {
  std::fprintf(err,
               "curio-sim serve: SYNC intervals in episodes against the %llu us period: %llu "
               "intervals, p50 %.0f / p99 %.0f / max %.0f us; late (> 1.5 periods) %llu, early "
               "(< 0.5 periods) %llu\n",
               static_cast<unsigned long long>(t.period_us),
               static_cast<unsigned long long>(t.intervals), t.p50_us, t.p99_us, t.max_us,
               static_cast<unsigned long long>(t.late), static_cast<unsigned long long>(t.early));
}

}  // namespace

CLI::App* add_serve_command(CLI::App* app, ServeCommandOptions* options) {
  CLI::App* cmd = app->add_subcommand(
      "serve",
      "Present the arm on a CAN bus as 7 CiA 402 joint nodes (ids 1-7) and the camera node "
      "(0x20), in lockstep: the world advances one control period per SYNC during an episode. "
      "Runs until SIGINT/SIGTERM (exit 130/143) or --exit-after-idle (exit 0). Protocol: "
      "docs/controller.md");
  cmd->add_option("--bus", options->bus, hal::kBusUrlHelp)
      ->check(curio::cli::bus_url_check())
      ->capture_default_str();
  add_physics_option(cmd, &options->physics);
  add_seed_option(cmd, &options->seed,
                  "run seed (as curio-controller --seed, curio-lab --seeds): the distractor walk "
                  "of the run; NMT reset of the camera node restarts it");
  add_world_params_options(cmd, &options->grasp_radius, &options->distractor_noise);
  cmd->add_option("--status-every", options->status_every_s,
                  "seconds between status lines on stderr (0: only at exit)")
      ->check(cli::kNonNegative)
      ->capture_default_str();
  cmd->add_option("--exit-after-idle", options->exit_after_idle_s,
                  "exit when no frame arrived for this many seconds (0: never)")
      ->check(cli::kNonNegative)
      ->capture_default_str();
  cmd->add_option("--period-us", options->period_us,
                  "the drives' control period in microseconds (a real arm's 10000): measure "
                  "the interval between the SYNCs of each episode against it and print p50 / "
                  "p99 / max with the late and early ones at exit, what a real drive would feel "
                  "of the controller's clock (0: not measured; the world steps once per SYNC "
                  "either way)")
      ->check(CLI::Range(uint64_t{0}, uint64_t{10'000'000}))
      ->capture_default_str();
  cmd->add_flag("--no-camera-node", options->no_camera_node,
                "no camera node 0x20 on the bus (a camera on the controller's computer, as "
                "curio-controller --camera COMMAND expects): it sends and answers nothing, and "
                "each episode starts at the first SYNC after the previous one's 50 steps");
  cmd->add_option("--camera-stream", options->camera_stream,
                  "stream the scene as a camera would on this Unix socket: raw RGB24 frames of "
                  "--camera-size at --camera-fps, each the scene at that wall-clock instant "
                  "(read it with ffmpeg -f rawvideo -pix_fmt rgb24 -video_size WxH -i unix:PATH)");
  cmd->add_option("--camera-size", options->camera_size,
                  "WIDTHxHEIGHT of the streamed frames: square pixels, the 64x64 image's field of "
                  "view widened on the longer side (min side 8 to 320)")
      ->capture_default_str();
  cmd->add_option("--camera-fps", options->camera_fps, "frames per second streamed (1 to 1000)")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  cmd->add_option("--positions", options->positions,
                  "append every episode's final positions to this CSV (episode,ball_x,ball_y,"
                  "distractor_x,distractor_y,grasped; a replayed episode again): what a tracker would "
                  "give curio-lab score");
  cmd->add_option("--joint-speed-limit", options->joint_speed_limit,
                  "fault injection: the ODE joints' motors turn at most this fast (rad/s), so a "
                  "joint told to move faster lags behind its target and the drive raises a "
                  "following error (EMCY 0x8611) once 0x6065/0x6066 are set (0: no limit; the "
                  "kinematic model never lags)")
      ->check(cli::kNonNegative)
      ->capture_default_str();
  return cmd;
}

int run_serve(const ServeCommandOptions& options, std::FILE* err) {
  serve::ServeOptions so;
  if (!parse_physics(options.physics, &so.physics)) {  // --physics is checked when parsed
    std::fprintf(err, "curio-sim: unknown physics '%s' (kinematic or ode)\n",
                 options.physics.c_str());
    return 2;
  }
  so.world.grasp_radius = options.grasp_radius;
  so.world.distractor_noise = options.distractor_noise;
  so.seed = options.seed;
  so.period_us = options.period_us;
  so.joint_speed_limit_rad_s = options.joint_speed_limit;
  so.log = err;  // each joint's missed heartbeat and standstill, one line each
  std::string error;
  auto bus = hal::open_bus(options.bus, &error);
  if (!bus) {
    std::fprintf(err, "curio-sim: cannot open bus '%s': %s\n", options.bus.c_str(), error.c_str());
    return 1;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  so.camera_node = !options.no_camera_node;
  std::unique_ptr<serve::CameraStream> stream;
  if (!options.camera_stream.empty()) {
    serve::CameraStreamOptions co;
    co.socket_path = options.camera_stream;
    co.fps = options.camera_fps;
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(options.camera_size.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' ||
        w < 8 || h < 8 || w > 4096 || h > 4096 || (w < h ? w : h) > kMaxRenderSide) {
      std::fprintf(err, "curio-sim: --camera-size: '%s' is not WIDTHxHEIGHT with the smaller side 8 to %d\n",
                   options.camera_size.c_str(), kMaxRenderSide);
      return 2;
    }
    co.width = w;
    co.height = h;
    stream = std::make_unique<serve::CameraStream>();
    if (const std::string why = stream->open(co); !why.empty()) {
      std::fprintf(err, "curio-sim: --camera-stream: %s\n", why.c_str());
      return 1;
    }
  }
  std::FILE* positions = nullptr;
  if (!options.positions.empty()) {
    positions = std::fopen(options.positions.c_str(), "a");
    if (positions == nullptr) {
      std::fprintf(err, "curio-sim: --positions: cannot open %s\n", options.positions.c_str());
      return 1;
    }
  }
  serve::ArmNodes nodes(bus.get(), so);
  std::fprintf(err, "curio-sim serve: %s physics, seed %llu, on %s (joints 1-7, %s)\n",
               physics_name(so.physics), static_cast<unsigned long long>(so.seed),
               options.bus.c_str(), so.camera_node ? "camera 0x20" : "no camera node");
  if (stream)
    std::fprintf(err, "curio-sim serve: streaming the scene, %s RGB24 at %g frames/s, on %s\n",
                 options.camera_size.c_str(), options.camera_fps, options.camera_stream.c_str());
  uint64_t positions_written_at = 0;  // episode starts counted when the last line was written
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  auto last_status = t0;
  auto last_frame = t0;
  uint64_t frames_seen = 0;
  while (g_signal.load() == 0) {
    uint64_t wait_us = 50'000;
    if (stream) {
      const auto us = std::chrono::duration_cast<std::chrono::microseconds>(
          clock::now().time_since_epoch()).count();
      const uint64_t due = stream->tick(static_cast<uint64_t>(us), nodes.world().state());
      wait_us = due < wait_us ? due : wait_us;
    }
    const hal::CanStatus s = nodes.poll(wait_us);
    const auto now = clock::now();
    if (positions != nullptr && nodes.episode_done() &&
        nodes.counters().episodes != positions_written_at) {
      positions_written_at = nodes.counters().episodes;
      const SceneState& st = nodes.world().state();
      std::fprintf(positions, "%u,%.17g,%.17g,%.17g,%.17g,%d\n", static_cast<unsigned>(nodes.episode()),
                   st.ball.x, st.ball.y, st.distractor.x, st.distractor.y, st.grasped ? 1 : 0);
      std::fflush(positions);
    }
    if (nodes.counters().frames_in != frames_seen) {
      frames_seen = nodes.counters().frames_in;
      last_frame = now;
    }
    if (s != hal::CanStatus::kOk && s != hal::CanStatus::kTimeout && s != hal::CanStatus::kEmpty) {
      std::fprintf(err, "curio-sim serve: bus: %s\n", hal::to_string(s));
      if (s == hal::CanStatus::kIoError) return 1;
    }
    if (options.status_every_s > 0 &&
        std::chrono::duration<double>(now - last_status).count() >= options.status_every_s) {
      print_counters(err, nodes.counters(), std::chrono::duration<double>(now - t0).count());
      last_status = now;
    }
    if (options.exit_after_idle_s > 0 &&
        std::chrono::duration<double>(now - last_frame).count() >= options.exit_after_idle_s)
      break;
  }
  print_counters(err, nodes.counters(), std::chrono::duration<double>(clock::now() - t0).count());
  if (stream) {
    const serve::CameraStreamCounters& c = stream->counters();
    std::fprintf(err, "curio-sim serve: camera stream: %llu frames rendered, %llu sent, %llu dropped, %llu readers\n",
                 static_cast<unsigned long long>(c.frames_rendered),
                 static_cast<unsigned long long>(c.frames_sent),
                 static_cast<unsigned long long>(c.frames_dropped),
                 static_cast<unsigned long long>(c.readers));
  }
  if (positions != nullptr) std::fclose(positions);
  if (so.period_us > 0) print_sync_timing(err, nodes.sync_timing());
  const int sig = g_signal.load();
  return sig != 0 ? 128 + sig : 0;  // 130 after SIGINT, 143 after SIGTERM
}

}  // namespace curio::sim
