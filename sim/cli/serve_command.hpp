// `curio-sim serve --bus URL`: the simulated arm on a CAN bus (7 CiA 402 joints + camera),
// in lockstep with the controller's SYNC, until SIGINT/SIGTERM.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

namespace curio::sim {

struct ServeCommandOptions {
  std::string bus = "udp:127.0.0.1:29500";
  std::string physics = "ode";
  uint64_t seed = 0;
  double grasp_radius = 0.1;
  double distractor_noise = 0.1;
  double status_every_s = 10.0;  // status line period on stderr (0: only at exit)
  double exit_after_idle_s = 0;  // > 0: exit when no frame arrived for this long
  uint64_t period_us = 0;        // > 0: measure the SYNC intervals against this period
  // A camera on the controller's computer (sim/serve/camera_stream.hpp, docs/hil.md):
  bool no_camera_node = false;   // node 0x20 not on the bus; episodes start themselves
  std::string camera_stream;     // Unix socket streaming the scene as raw RGB24 ("" : none)
  std::string camera_size = "64x64";
  double camera_fps = 50.0;
  std::string positions;         // CSV of every episode's final positions and grasp (a tracker's output)
  double joint_speed_limit = 0;  // > 0: the ODE joints' motor speed limit, rad/s (fault injection)
};

CLI::App* add_serve_command(CLI::App* app, ServeCommandOptions* options);

// Exit status: 0 after the idle limit, 130/143 after SIGINT/SIGTERM, 1 if the bus cannot be
// opened or fails. The options are checked when parsed (add_serve_command).
int run_serve(const ServeCommandOptions& options, std::FILE* err);

}  // namespace curio::sim
