// What one run over the bus is asked to do and what it gives back: BusRunOptions (the run's
// lab::RunSpec, the controller's configuration, the journal, the host's stop request, a camera
// on this computer) and BusRunResult (the run's lab::RunResult, the bus's counters, the arm's
// world and identities, how the drives were stopped). Apart from run_over_bus (bus_run.hpp) so
// the files of its steps (arm_bring_up, bus_journal, bus_report, camera_run)
// include these types without including the run that calls them.
#pragma once
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>

#include "firmware/app/controller.hpp"
#include "firmware/protocol/world_identity.hpp"
#include "host_tools/controller/bus_history.hpp"
#include "host_tools/experiment/run.hpp"

namespace curio::app::host {

struct BusRunOptions {
  lab::RunSpec spec;              // algorithm, seed, σ, bootstrap, episodes, D, ... (as curio-lab)
  ControllerConfig controller;    // timeouts, retries, limits; want_image forced on for latents
  std::FILE* progress = nullptr;  // progress lines (null: none)
  double progress_every_s = 2.0;
  CycleProbe* probe = nullptr;  // per-SYNC-cycle timing (benchmarks)
  PeriodPacer* pacer = nullptr;  // wall-clock control periods (null: as fast as the arm answers)
  // Journal (host_tools/journal/run_journal.hpp): empty = none. Every archived episode is
  // appended (fdatasync every journal_sync_every records). resume: rebuild the explorer and
  // the results from the journal by replay, then continue; the arm is brought up without an
  // NMT reset so `curio-sim serve` keeps its world (a reset restarts it from its seed) and
  // replays the episode that was in flight.
  std::string journal_path;
  bool resume = false;
  uint32_t journal_sync_every = 1;
  // bus_history.hpp: empty = none. The run's fault counters over all its processes, rewritten
  // whenever they change; a resume starts from what it holds.
  std::string bus_history_path;
  // The host's stop request (a signal handler writes the signal's number): the run ends at
  // once, with a controlled stop of the arm; BusRunResult::stop_signal says which.
  const volatile int* stop_signal = nullptr;
  // A camera on the controller's computer (controller.camera_on_bus false; camera_run.hpp):
  // where the capture takes the frame, and a step after each archived episode ("" or why the
  // run stops, e.g. a frame that cannot be saved).
  FrameSource* frame_source = nullptr;
  std::function<std::string(const EpisodeRecord&)> after_episode;
};

struct BusRunResult {
  lab::RunResult run;  // run.error non-empty: the run stopped early
  ControllerCounters counters;
  protocol::IsoTpCounters image;
  uint8_t physics = 0xFF;    // what the camera node reports (0 kinematic, 1 ODE)
  // What the camera node published as its world (0x2003; arm_bring_up.hpp): the run's own, or
  // the run was refused. world_published false: a real arm (no 0x2003).
  protocol::WorldIdentity world;
  bool world_published = false;
  double seconds = 0.0;      // wall time of the episodes (after start_arm)
  uint64_t frames_sent = 0;  // by the controller, all episodes
  uint64_t frames_received = 0;
  // Camera 0x2000.2 = 1: the arm's scenes are a function of (seed, episode), so a replay or an
  // episode after a node reboot is the one an undisturbed run has (curio-sim serve).
  bool episode_indexed = false;
  // Non-empty: why a fault may have changed this run's results (replays or node reboots on an
  // arm without episode-indexed scenes). The run completed; its results are marked.
  std::string inexact;
  // Counters over every process of the run (earlier ones from bus_history_path, then this one);
  // equal to `counters` for a run that was never resumed.
  BusHistory history;
  int resumed_episodes = 0;    // replayed from the journal (resume)
  // How the run ended on the drives (controlled_stop.hpp): every end of a run that reached the
  // arm is a controlled stop; stop_signal is the signal that asked for it (0: none).
  StopReport stop;
  bool stopped = false;  // stop_arm() ran
  int stop_signal = 0;
  // Every node's CiA 301 identity, read at start-up (identities_read false: the arm did not
  // answer that far).
  NodeIdentity nodes[kArmNodes];
  bool identities_read = false;
  std::string journal_notice;  // what the resume found (torn tail dropped, ...)
};

}  // namespace curio::app::host
