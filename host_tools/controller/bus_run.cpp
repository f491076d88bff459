#include "host_tools/controller/bus_run.hpp"

#include <chrono>
#include <cstdio>
#include <memory>

#include "host_tools/controller/arm_bring_up.hpp"
#include "host_tools/controller/bus_journal.hpp"
#include "host_tools/controller/fault_text.hpp"
#include "host_tools/experiment/run_explorer.hpp"
#include "host_tools/experiment/run_recorder.hpp"
#include "host_tools/journal/run_journal.hpp"

namespace curio::app::host {

namespace {

// The episodes of a run over the bus, one after another until the explorer is done or an
// episode fails: each episode the Controller runs (with its retries and recoveries) is recorded
// as curio-lab records it, the bus history is rewritten when the fault counters change, and a
// progress line goes out every progress_every_s seconds.
using Clock = std::chrono::steady_clock;

void print_progress(std::FILE* to, int n, int total, const lab::RunRecorder& recorder, double rate,
                    const ControllerCounters& c) {
  std::fprintf(to,
               "curio-controller: %d/%d episodes, ratio %.3f, %llu grasps, %.0f episodes/s, "
               "%llu faults, %llu replays\n",
               n, total, recorder.ratio(), static_cast<unsigned long long>(recorder.grasps()), rate,
               static_cast<unsigned long long>(c.fault_total),
               static_cast<unsigned long long>(c.replays));
  std::fflush(to);
}

// Runs the remaining episodes. Sets out->seconds (and out->run.seconds) to their wall time, and
// out->run.error when an episode fails (episode_failure_text), or when `journal` (null: none)
// cannot take an episode: then the error names the file and the cause (a full disk), and the
// run stops at once, its journal whole up to the episode before.
void run_episodes(Controller& controller, const Explorer& explorer, lab::RunRecorder& recorder,
                  BusHistoryFile& history, const journal::host::RunJournal* journal,
                  const BusRunOptions& options, BusRunResult* out) {
  const int total = explorer.total_episodes();
  const auto t0 = Clock::now();
  auto last_progress = t0;
  while (!explorer.done()) {
    const AppStatus s = controller.run_episode();
    if (s == AppStatus::kJournalError && journal != nullptr) {
      // The episode ran and is in the archive, but not on disk: stop before the next one.
      out->run.error = journal->write_failure(static_cast<uint32_t>(controller.last_episode().episode)) +
                       "; the journal keeps every episode before it: make room, then run "
                       "again with --resume";
      break;
    }
    if (s != AppStatus::kOk) {
      out->run.error = "episode " + std::to_string(explorer.episode()) + ": " +
                       episode_failure_text(controller, s, options.controller);
      break;
    }
    const EpisodeRecord& e = controller.last_episode();
    recorder.record_episode(e.exploit, e.module, e.progress, e.ball[0], e.ball[1], e.grasped);
    history.save_if_changed(controller.counters());
    if (options.after_episode) {
      if (std::string why = options.after_episode(e); !why.empty()) {
        out->run.error = "episode " + std::to_string(e.episode) + ": " + why;
        break;
      }
    }
    const int n = explorer.episode();
    const auto now = Clock::now();
    if (options.progress &&
        (std::chrono::duration<double>(now - last_progress).count() >= options.progress_every_s ||
         n == total)) {
      const double dt = std::chrono::duration<double>(now - t0).count();
      print_progress(options.progress, n, total, recorder,
                     dt > 0 ? (n - out->resumed_episodes) / dt : 0.0, controller.counters());
      last_progress = now;
    }
  }
  out->seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  out->run.seconds = out->seconds;
}


// The end of a run that got the arm: a rebooted node may run another world now (its world
// again), the verdicts of a complete run, the arm stopped, the counters over every process,
// and whether a fault may have changed the results.
void close_run(Controller& controller, lab::RunRecorder& recorder, BusHistoryFile& history,
               BusRunResult* out) {
  lab::RunResult& r = out->run;
  if (r.error.empty() && controller.counters().node_reboots > 0) {
    if (std::string m = world_mismatch(controller, r.spec); !m.empty())
      r.error =
          "after " + std::to_string(controller.counters().node_reboots) + " node reboots, " + m;
  }
  if (r.error.empty()) recorder.finish();
  out->stop = controller.stop_arm();
  out->stopped = true;
  out->counters = controller.counters();
  out->history = history.total(out->counters);
  history.save(out->counters);
  const BusHistory& c = out->history;
  if (!out->episode_indexed && (c.replays > 0 || c.node_reboots > 0))
    out->inexact = std::to_string(c.replays) + " replayed attempts and " +
                   std::to_string(c.node_reboots) +
                   " node reboots on an arm that does not promise episode-indexed scenes "
                   "(camera 0x2000.2): a replayed episode may differ from the undisturbed one";
  out->image = controller.image_counters();
  out->frames_sent = out->counters.frames_sent;
  out->frames_received = out->counters.frames_received;
}

}  // namespace

BusRunResult run_over_bus(hal::CanBus* bus, const BusRunOptions& options,
                          const std::function<void(const Explorer&)>& on_finish) {
  BusRunResult out;
  out.run.spec = options.spec;
  lab::RunExplorer x;
  if (!lab::make_run_explorer(options.spec, &x, &out.run.error)) return out;
  // The journal and the fault history first: a refused resume leaves the arm untouched.
  BusJournal journal;
  if (!open_bus_journal(options, x.config, &journal, &out)) return out;
  BusHistoryFile history(options.bus_history_path, options.progress);
  if (journal.resume && !history.load_earlier(&out.run.error)) return out;
  ControllerConfig config = options.controller;
  // Keep the nodes' state: an NMT reset would restart the simulated world from its seed.
  if (journal.resume) config.reset_nodes = false;
  auto controller = std::make_unique<Controller>();
  controller->set_frame_source(options.frame_source);
  if (!bring_up_arm(bus, config, *x.explorer, x.encoder.get(), options.probe,
                    options.stop_signal, *controller, &out)) {
    if (options.stop_signal != nullptr) out.stop_signal = *options.stop_signal;
    return out;
  }
  lab::RunRecorder recorder(*x.explorer, x.rep, &out.run);
  if (!start_bus_journal(journal, options, x.config, *x.explorer, recorder, *controller, &out)) {
    out.stop = controller->stop_arm();
    out.stopped = true;
    out.counters = controller->counters();
    return out;
  }
  history.save(controller->counters());
  controller->set_period_pacer(options.pacer);
  run_episodes(*controller, *x.explorer, recorder, history, journal.file.get(), options, &out);
  close_run(*controller, recorder, history, &out);
  if (on_finish) on_finish(*x.explorer);
  if (options.stop_signal != nullptr) out.stop_signal = *options.stop_signal;
  return out;
}

}  // namespace curio::app::host
