#include "host_tools/controller/bus_run.hpp"

#include <memory>

#include "host_tools/controller/arm_bring_up.hpp"
#include "host_tools/controller/arm_world.hpp"
#include "host_tools/controller/bus_journal.hpp"
#include "host_tools/controller/episode_loop.hpp"
#include "host_tools/experiment/run_explorer.hpp"
#include "host_tools/experiment/run_recorder.hpp"

namespace curio::app::host {

namespace {

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
