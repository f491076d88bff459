// The controller scenario shared by the Cortex-M7 image (QEMU, firmware.app.qemu_controller)
// and its host twin (firmware.app.host_controller): the real firmware/app Controller runs a
// short MGE-EFR exploration against the in-image FakeArm over the in-image ImageBus, and the
// run is reduced to checksums that both machines must print identically.
//   archive checksum  FNV-1a over every archived θ and outcome (float bit patterns)
//   wire checksum     FNV-1a over the integer protocol path: per episode the frames sent and
//                     received, the grasp flag and the final ball cell; then the counters
//   hand checksum     FNV-1a over the fake arm's final hand position per episode, rounded
//                     to float32 (as outcomes are). The float64 hand positions themselves
//                     legitimately differ between the machines: libm's cos/sin (newlib on
//                     the Cortex-M7, glibc on x86-64) differ in the last bits (measured: 13
//                     of these 70 episodes, 1–6 ulp in x or y); float32 rounding, the grasp
//                     decisions and everything archived agree.
// Firmware-clean: no heap (everything in static storage), no OS.
#pragma once
#include <cstdint>

#include "firmware/app/controller.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "tests/app/qemu_app/image_bus.hpp"
#include "firmware/explore/fnv1a.hpp"

namespace curio::test {

// Host golden values of run_controller_scenario() (tests/app/qemu_app/host_main.cpp
// prints them); update them, and say why in the commit, when the algorithm, the controller's
// protocol or the world legitimately change.
inline constexpr uint32_t kControllerArchiveChecksum = 0xc722b816u;
inline constexpr uint32_t kControllerWireChecksum = 0x1353d825u;
inline constexpr uint32_t kControllerHandChecksum = 0xb42d9677u;

inline constexpr uint64_t kScenarioSeed = 0;
inline constexpr int kScenarioBootstrap = 20;
inline constexpr int kScenarioEpisodes = 50;
inline constexpr float kScenarioSigma = 0.05f;
inline constexpr double kScenarioGraspRadius = 0.1;
inline constexpr double kScenarioDistractorNoise = 0.1;

// The scenario's exploration (MGE-EFR), for the controller and for the in-process oracle.
inline ExplorerConfig scenario_explorer_config() {
  ExplorerConfig config;
  set_efr_modules(config, Algorithm::kMge);
  config.n_bootstrap = kScenarioBootstrap;
  config.n_episodes = kScenarioEpisodes;
  config.sigma = kScenarioSigma;
  config.seed = kScenarioSeed;
  return config;
}

// SPEC §4: cell of one coordinate on the 30×30 grid over [-1,1]² (host_tools/lab's rule).
inline int ratio_cell_of(double v) {
  if (!(v >= -1.0 && v <= 1.0)) return -1;
  const int c = static_cast<int>((v + 1.0) * 0.5 * 30);
  return c >= 30 ? 29 : c;
}

struct ScenarioResult {
  app::AppStatus start = app::AppStatus::kNotInitialised;
  app::AppStatus last = app::AppStatus::kNotInitialised;
  Status explorer_init = Status::kOk;
  int episodes = 0;       // archived
  int grasps = 0;
  int visited_cells = 0;  // of 900
  uint32_t archive_checksum = 0;
  uint32_t wire_checksum = 0;
  uint32_t hand_checksum = 0;
  uint64_t virtual_us = 0;  // bus time at the end
  app::ControllerCounters counters;
  FakeArm::Counters arm;
};

// Everything the run needs, in one object for static storage (~100 KB with capacity 128).
struct ControllerScenario {
  Explorer explorer;
  app::Controller controller;
  ImageBus bus;
  FakeArm arm;
  uint8_t visited[900] = {};

  ScenarioResult run() {
    ScenarioResult r;
    r.explorer_init = explorer.init(scenario_explorer_config());
    if (r.explorer_init != Status::kOk) return r;

    bus.attach(&arm);
    arm.init(kScenarioSeed, kScenarioGraspRadius, kScenarioDistractorNoise, bus.arm_out());
    app::ControllerConfig cc;  // defaults: ground truth only, 100 ms heartbeats, 3 attempts
    r.start = controller.init(&bus, &explorer, cc);
    if (r.start != app::AppStatus::kOk) return r;
    r.start = controller.start_arm();
    if (r.start != app::AppStatus::kOk) return r;

    Fnv1a wire;
    Fnv1a hand;
    for (uint8_t& v : visited) v = 0;
    while (!explorer.done()) {
      r.last = controller.run_episode();
      if (r.last != app::AppStatus::kOk) break;
      const app::EpisodeRecord& e = controller.last_episode();
      ++r.episodes;
      if (e.grasped) ++r.grasps;
      const int cx = ratio_cell_of(static_cast<double>(e.ball[0]));
      const int cy = ratio_cell_of(static_cast<double>(e.ball[1]));
      int cell = -1;
      if (cx >= 0 && cy >= 0) {
        cell = cy * 30 + cx;
        if (visited[cell] == 0) {
          visited[cell] = 1;
          ++r.visited_cells;
        }
      }
      wire.add_u32(controller.last_frames_sent());
      wire.add_u32(controller.last_frames_received());
      wire.add_u32(e.grasped ? 1u : 0u);
      wire.add_u32(static_cast<uint32_t>(cell));
      wire.add_u32(static_cast<uint32_t>(e.attempts));
      hand.add_float(static_cast<float>(arm.world().hand_x));
      hand.add_float(static_cast<float>(arm.world().hand_y));
    }
    const app::ControllerCounters& c = controller.counters();
    wire.add_u64(c.frames_sent);
    wire.add_u64(c.frames_received);
    wire.add_u64(c.sync_cycles);
    wire.add_u64(c.fault_total);
    wire.add_u64(c.replays);
    wire.add_u64(c.unexpected_frames + c.malformed_frames + c.foreign_frames);
    r.wire_checksum = wire.h;
    r.hand_checksum = hand.h;

    Fnv1a archive;
    archive.add_archive(explorer.archive());
    r.archive_checksum = archive.h;
    r.counters = c;
    r.arm = arm.counters();
    r.virtual_us = bus.now_us();
    return r;
  }
};

// The pass/fail rules both machines apply (besides the golden checksums).
inline int scenario_failures(const ScenarioResult& r, const ControllerScenario& s) {
  int failures = 0;
  if (r.explorer_init != Status::kOk) ++failures;
  if (r.start != app::AppStatus::kOk) ++failures;
  if (r.last != app::AppStatus::kOk) ++failures;
  if (r.episodes != kScenarioBootstrap + kScenarioEpisodes) ++failures;
  if (!s.explorer.done()) ++failures;
  if (r.counters.fault_total != 0 || r.counters.replays != 0) ++failures;
  if (r.counters.sync_cycles != static_cast<uint64_t>(r.episodes) * kStepsPerEpisode) ++failures;
  if (r.counters.malformed_frames != 0 || r.counters.unexpected_frames != 0) ++failures;
  if (r.arm.dropped != 0 || r.arm.rejected_targets != 0 || r.arm.sdo_aborts != 0) ++failures;
  return failures;
}

}  // namespace curio::test
