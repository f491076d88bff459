#include "host_tools/controller/episode_loop.hpp"

#include <chrono>
#include <cstdio>

#include "host_tools/controller/fault_text.hpp"

namespace curio::app::host {

namespace {

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

}  // namespace

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

}  // namespace curio::app::host
