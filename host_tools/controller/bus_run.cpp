#include "host_tools/controller/bus_run.hpp"

#include <chrono>
#include <memory>

#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/nn/encoder.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "host_tools/journal/run_journal.hpp"
#include "host_tools/experiment/representations.hpp"
#include "host_tools/experiment/run_recorder.hpp"

namespace curio::app::host {

std::string fault_summary(const ControllerCounters& c) {
  std::string s;
  for (size_t i = 1; i < kFaultKinds; ++i) {
    if (c.faults[i] == 0) continue;
    s += std::string(to_string(static_cast<Fault>(i))) + " " + std::to_string(c.faults[i]) + "; ";
  }
  if (s.empty()) return "no faults";
  s += "last: " + std::string(to_string(c.last_fault)) + " (node " +
       std::to_string(c.last_fault_node) + ")";
  return s;
}

std::string fatal_fault_text(const ControllerCounters& c, Fault fatal) {
  const std::string node = std::to_string(c.last_fault_node);
  if (fatal == Fault::kOtherMaster)
    return "another master is on this bus: " + std::to_string(c.other_master_frames) +
           " NMT/SYNC/RPDO/SDO-request/capture frames this controller did not send (is a "
           "second curio-controller running on it?); its frames change the arm's scene, so "
           "this run cannot continue";
  if (fatal == Fault::kDuplicateNode)
    return "two nodes answer as node " + node + " (" + std::to_string(c.duplicate_answers) +
           " duplicate SDO answers): a second arm (another curio-sim serve?) is on this bus";
  return to_string(fatal);
}

namespace {

// The arm's run seed (camera 0x2003) against the run's: "" when they agree or the arm has
// none (a real arm); else what is wrong.
std::string seed_mismatch(Controller& controller, int64_t run_seed) {
  uint32_t arm_seed = 0;
  if (!controller.read_camera_object(protocol::od::kRunSeed, 0, &arm_seed)) return "";
  if (arm_seed == static_cast<uint32_t>(run_seed)) return "";
  return "the arm's world runs seed " + std::to_string(arm_seed) + " but this run is seed " +
         std::to_string(run_seed) + " (start curio-sim serve with --seed " +
         std::to_string(run_seed) + ")";
}

std::string seconds_text(uint64_t us) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g s", static_cast<double>(us) / 1e6);
  return buf;
}

}  // namespace

std::string episode_failure_text(const Controller& controller, AppStatus s,
                                 const ControllerConfig& config) {
  const Fault fatal = controller.fatal_fault();
  if (fatal != Fault::kNone) return fatal_fault_text(controller.counters(), fatal);
  std::string text = std::string(to_string(s)) + " (" + fault_summary(controller.counters()) + "); ";
  // Every attempt ran (the arm came back before each): the faults recur, the arm is there.
  if (s == AppStatus::kEpisodeFailed && controller.last_episode().attempts >= config.max_attempts)
    return text + "each of its " + std::to_string(config.max_attempts) +
           " attempts (--max-attempts) hit a fault, though the arm came back between them";
  return text + "the arm did not come back within the hold time (" +
         seconds_text(config.recovery_timeout_us) + ", --hold-time)";
}

BusRunResult run_over_bus(hal::CanBus* bus, const BusRunOptions& options,
                          const std::function<void(const Explorer&)>& on_finish) {
  using clock = std::chrono::steady_clock;
  BusRunResult out;
  lab::RunResult& r = out.run;
  const lab::RunSpec& spec = options.spec;
  r.spec = spec;

  const lab::Representation* rep = nullptr;
  if (spec.algorithm.outcome == lab::OutcomeSource::kLatents) {
    rep = lab::find_representation(spec.algorithm.representation);
    if (rep == nullptr) {
      r.error =
          "no weights for representation '" + spec.algorithm.representation + "' in this build";
      return out;
    }
  }
  ExplorerConfig config;
  if (const Status s = lab::make_explorer_config(spec, &config); s != Status::kOk) {
    r.error = std::string("invalid explorer configuration: ") + to_string(s);
    return out;
  }
  // Host: one allocation each at init (firmware: static storage).
  auto explorer = std::make_unique<Explorer>();
  if (const Status s = explorer->init(config); s != Status::kOk) {
    r.error = std::string("explorer init failed: ") + to_string(s);
    return out;
  }
  std::unique_ptr<nn::Encoder> encoder;
  if (rep) encoder = std::make_unique<nn::Encoder>(*rep->model);
  // The journal first: a resume under another configuration is refused before the arm moves.
  std::unique_ptr<journal::host::RunJournal> journal;
  bool resume = false;
  ControllerConfig controller_config = options.controller;
  if (!options.journal_path.empty()) {
    journal =
        journal::host::RunJournal::open(options.journal_path, &r.error, options.journal_sync_every);
    if (!journal) return out;
    const journal::JournalStatus js = journal->scan().status;
    // Nothing journaled yet (absent, or cut while being created): a resume starts afresh.
    resume = options.resume && js != journal::JournalStatus::kNoJournal &&
             js != journal::JournalStatus::kTornHeader;
    if (options.resume && !resume)
      out.journal_notice = "nothing journaled yet (" + journal::host::describe(journal->scan()) +
                           "): starting at episode 0";
    if (resume) {
      if (js != journal::JournalStatus::kOk) {
        r.error = options.journal_path +
                  ": cannot resume: " + journal::host::describe(journal->scan()) +
                  "; nothing was changed";
        return out;
      }
      const journal::RunIdentity& jid = journal->scan().header.identity;
      const std::string diff = journal::host::describe_difference(
          jid, journal::host::identity_of(spec, config, jid.physics));
      if (!diff.empty()) {
        r.error = options.journal_path + ": cannot resume: " + diff + "; nothing was changed";
        return out;
      }
      // Keep the nodes' state: an NMT reset would restart the simulated world from its seed.
      controller_config.reset_nodes = false;
    }
  }
  // The fault counters of the run's earlier processes (a resumed run), kept beside the journal;
  // read before the arm moves, like the journal.
  BusHistory earlier;
  if (!options.bus_history_path.empty() && resume &&
      !load_bus_history(options.bus_history_path, &earlier, &r.error))
    return out;
  auto controller = std::make_unique<Controller>();
  if (const AppStatus s = controller->init(bus, explorer.get(), controller_config, encoder.get());
      s != AppStatus::kOk) {
    r.error = std::string("controller init failed: ") + to_string(s);
    return out;
  }
  controller->set_cycle_probe(options.probe);
  if (const AppStatus s = controller->start_arm(); s != AppStatus::kOk) {
    const Fault fatal = controller->fatal_fault();
    r.error = fatal != Fault::kNone ? fatal_fault_text(controller->counters(), fatal)
                                    : std::string("the arm did not come up: ") + to_string(s) +
                                          " (" + fault_summary(controller->counters()) +
                                          "); is `curio-sim serve` running on this bus?";
    out.counters = controller->counters();
    return out;
  }
  out.physics = controller->query_physics();
  uint32_t indexed = 0;
  out.episode_indexed =
      controller->read_camera_object(protocol::od::kEpisodeControl,
                                     protocol::od::kEpisodeIndexedSub, &indexed) &&
      indexed == 1;
  if (std::string m = seed_mismatch(*controller, spec.explorer.seed); !m.empty()) {
    r.error = m;
    controller->stop_arm();
    out.counters = controller->counters();
    return out;
  }
  if (out.physics == 0) r.spec.physics = sim::Physics::kKinematic;
  if (out.physics == 1) r.spec.physics = sim::Physics::kOde;

  lab::RunRecorder recorder(*explorer, rep, &r);
  const int total = explorer->total_episodes();
  if (journal) {
    const journal::RunIdentity id = journal::host::identity_of(spec, config, out.physics);
    const bool ok = resume ? journal->resume(
                                 id, explorer.get(),
                                 [&](const journal::EpisodeEntry& e, const Explorer&) {
                                   recorder.record_episode(e.exploit, e.module, e.progress,
                                                           e.ball[0], e.ball[1], e.grasped);
                                 },
                                 &r.error, &out.journal_notice)
                           : journal->start(id, &r.error);
    if (!ok) {
      controller->stop_arm();
      out.counters = controller->counters();
      return out;
    }
    out.resumed_episodes = explorer->episode();
    controller->set_journal(&journal->writer());
    if (options.progress && options.resume)
      std::fprintf(options.progress, "curio-controller: resume %s: %s; continuing at episode %d\n",
                   options.journal_path.c_str(), out.journal_notice.c_str(), explorer->episode());
  }

  auto save_history = [&](const ControllerCounters& now) {
    std::string why;
    if (!options.bus_history_path.empty() &&
        !save_bus_history(options.bus_history_path, combined(earlier, now), &why) &&
        options.progress)
      std::fprintf(options.progress, "curio-controller: warning: %s\n", why.c_str());
  };
  auto judged = [](const ControllerCounters& c) {
    return c.fault_total + c.replays + c.capture_retries + c.node_reboots;
  };
  save_history(controller->counters());
  uint64_t saved = judged(controller->counters());

  const auto t0 = clock::now();
  auto last_progress = t0;
  while (!explorer->done()) {
    const AppStatus s = controller->run_episode();
    if (s != AppStatus::kOk) {
      r.error = "episode " + std::to_string(explorer->episode()) + ": " +
                episode_failure_text(*controller, s, options.controller);
      break;
    }
    const EpisodeRecord& e = controller->last_episode();
    recorder.record_episode(e.exploit, e.module, e.progress, e.ball[0], e.ball[1], e.grasped);
    if (judged(controller->counters()) != saved) {
      save_history(controller->counters());
      saved = judged(controller->counters());
    }
    const int n = explorer->episode();
    const auto now = clock::now();
    if (options.progress &&
        (std::chrono::duration<double>(now - last_progress).count() >= options.progress_every_s ||
         n == total)) {
      const double dt = std::chrono::duration<double>(now - t0).count();
      std::fprintf(options.progress,
                   "curio-controller: %d/%d episodes, ratio %.3f, %llu grasps, %.0f episodes/s, "
                   "%llu faults, %llu replays\n",
                   n, total, recorder.ratio(), static_cast<unsigned long long>(recorder.grasps()),
                   dt > 0 ? (n - out.resumed_episodes) / dt : 0.0,
                   static_cast<unsigned long long>(controller->counters().fault_total),
                   static_cast<unsigned long long>(controller->counters().replays));
      std::fflush(options.progress);
      last_progress = now;
    }
  }
  out.seconds = std::chrono::duration<double>(clock::now() - t0).count();
  r.seconds = out.seconds;
  // A node that rebooted may be another program now: the seed again.
  if (r.error.empty() && controller->counters().node_reboots > 0) {
    if (std::string m = seed_mismatch(*controller, spec.explorer.seed); !m.empty())
      r.error =
          "after " + std::to_string(controller->counters().node_reboots) + " node reboots, " + m;
  }
  if (r.error.empty()) recorder.finish();
  controller->stop_arm();
  out.counters = controller->counters();
  out.history = combined(earlier, out.counters);
  save_history(out.counters);
  const BusHistory& c = out.history;
  if (!out.episode_indexed && (c.replays > 0 || c.node_reboots > 0))
    out.inexact = std::to_string(c.replays) + " replayed attempts and " +
                  std::to_string(c.node_reboots) +
                  " node reboots on an arm that does not promise episode-indexed scenes "
                  "(camera 0x2000.2): a replayed episode may differ from the undisturbed one";
  out.image = controller->image_counters();
  out.frames_sent = out.counters.frames_sent;
  out.frames_received = out.counters.frames_received;
  if (on_finish) on_finish(*explorer);
  return out;
}

}  // namespace curio::app::host
