#include "host_tools/controller/bus_report.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "host_tools/controller/arm_bring_up.hpp"
#include "host_tools/controller/fault_text.hpp"
#include "host_tools/experiment/report.hpp"

namespace curio::app::host {

void print_bus_run(const BusRunResult& result) {
  const int done = static_cast<int>(result.run.final_ball.size());
  // Rates over the episodes this process ran (not those replayed from the journal).
  const int ran = done - result.resumed_episodes;
  std::fprintf(stderr,
               "curio-controller: %d episodes (%d replayed from the journal) in %.1f s "
               "(%.0f episodes/s), %.0f frames/episode sent + %.0f received; faults: %s\n",
               done, result.resumed_episodes, result.seconds,
               result.seconds > 0 ? ran / result.seconds : 0.0,
               ran > 0 ? static_cast<double>(result.frames_sent) / ran : 0.0,
               ran > 0 ? static_cast<double>(result.frames_received) / ran : 0.0,
               fault_summary(result.counters).c_str());
}

namespace {

// summary.json "bus": over every process of the run (a resumed run's earlier ones from
// bus_counters.json).
nlohmann::json bus_block(const BusRunResult& result) {
  const BusHistory& k = result.history;
  nlohmann::json faults = nlohmann::json::object();
  for (size_t i = 1; i < kFaultKinds; ++i)
    if (k.faults[i] > 0) faults[to_string(static_cast<Fault>(i))] = k.faults[i];
  nlohmann::json bus = {{"faults", faults},
                        {"fault_total", k.fault_total},
                        {"replays", k.replays},
                        {"capture_retries", k.capture_retries},
                        {"node_reboots", k.node_reboots},
                        {"controller_processes", k.processes},
                        {"episode_indexed_scenes", result.episode_indexed},
                        {"results", result.inexact.empty() ? "exact" : "may differ"}};
  if (!result.inexact.empty()) bus["why"] = result.inexact;
  if (result.stopped) {
    const StopReport& s = result.stop;
    bus["controlled_stop"] = {{"sent", s.sent},
                              {"complete", s.complete()},
                              {"quick_stopped_joints", s.quick_stopped},
                              {"standstill_joints", s.standstill},
                              {"disabled_joints", s.disabled},
                              {"standstill_s", s.standstill_us / 1e6}};
    if (!s.sent) bus["controlled_stop"]["skipped"] = s.skipped;
  }
  return bus;
}

// summary.json "nodes": every node's CiA 301 identity as read at start-up.
nlohmann::json nodes_block(const BusRunResult& result) {
  nlohmann::json nodes = nlohmann::json::array();
  for (int i = 0; i < kArmNodes; ++i) {
    const NodeIdentity& id = result.nodes[i];
    if (!id.read) continue;
    nodes.push_back({{"node", node_id(i)},
                     {"role", i == kCameraIndex ? "camera" : "joint " + std::to_string(i + 1)},
                     {"device_type", id.device_type},
                     {"vendor_id", id.vendor_id},
                     {"product_code", id.product_code},
                     {"revision", id.revision},
                     {"serial", id.serial}});
  }
  return nodes;
}

// The line summary.md gets under "notes" (and stderr, when the bus misbehaved).
std::string bus_note(const BusRunResult& result) {
  const BusHistory& k = result.history;
  const std::string verdict =
      result.inexact.empty()
          ? (k.fault_total > 0 ? "those of an undisturbed run (episode-indexed scenes)"
                               : "those of an undisturbed run")
          : "MAY DIFFER from an undisturbed run: " + result.inexact;
  char note[512];
  std::snprintf(note, sizeof note,
                "Over the bus: %llu faults, %llu replayed attempts, %llu capture retries, %llu "
                "node reboots; results: %s.",
                static_cast<unsigned long long>(k.fault_total),
                static_cast<unsigned long long>(k.replays),
                static_cast<unsigned long long>(k.capture_retries),
                static_cast<unsigned long long>(k.node_reboots), verdict.c_str());
  return note;
}

// Controllable-feature discovery (host_tools/experiment/controllability.hpp) from the run's
// learning progress, beside the ground truth when the goal space has one.
void print_verdict(const lab::RunResult& r) {
  if (r.verdicts.empty()) return;
  const std::string truth = lab::expected_verdict(r);
  std::printf("controllable (from learning progress alone): {%s}", lab::verdict_text(r).c_str());
  if (!truth.empty())
    std::printf("; the ball's %s: {%s}", truth == "ball" ? "module" : "latents", truth.c_str());
  std::printf("\n");
}

}  // namespace

int write_bus_report(lab::CampaignConfig campaign, const BusRunResult& result,
                     const WallClockPacer* periods, const RealtimeSettings& realtime) {
  const lab::RunResult& r = result.run;
  campaign.physics = r.spec.physics;
  const std::vector<lab::RunResult> results = {r};
  auto summary = lab::summarize_campaign(campaign, results, result.seconds);
  summary["bus"] = bus_block(result);
  if (result.identities_read) summary["nodes"] = nodes_block(result);
  if (result.world_published) summary["world"] = world_json(result.world);
  const std::string note = bus_note(result);
  summary["notes"] = {note};
  if (periods != nullptr) summary["control_periods"] = period_stats_json(*periods, realtime);
  std::vector<std::string> warnings;
  std::string error;
  if (!lab::write_report(campaign, results, summary, &warnings, &error)) {
    std::fprintf(stderr, "curio-controller: %s\n", error.c_str());
    return 1;
  }
  if (periods != nullptr) {
    bool gnuplot_missing = false;
    const std::string why = write_period_files(*periods, campaign.out_dir, &gnuplot_missing);
    if (!why.empty() && !gnuplot_missing) {
      std::fprintf(stderr, "curio-controller: %s\n", why.c_str());
      return 1;
    }
    if (!why.empty()) warnings.push_back("control_periods.png: " + why);
    const PeriodStats s = periods->stats();
    std::printf(
        "control periods of %lld us (%s): %lld periods, woke late p50 %.0f / p99 %.0f / max %.0f "
        "us, "
        "work p50 %.0f / p99 %.0f / max %.0f us, %lld overruns\n",
        static_cast<long long>(periods->period_us()),
        realtime.priority > 0 ? ("SCHED_FIFO " + std::to_string(realtime.priority)).c_str()
                              : "normal scheduling",
        static_cast<long long>(s.periods), s.late_p50, s.late_p99, s.late_max, s.work_p50,
        s.work_p99, s.work_max, static_cast<long long>(s.overruns));
  }
  for (const auto& w : warnings) std::fprintf(stderr, "curio-controller: warning: %s\n", w.c_str());
  std::printf("exploration ratio after %zu episodes: %.4f (%d grasps); results in %s/\n",
              r.final_ball.size(), r.ratio.empty() ? 0.0 : r.ratio.back(),
              r.grasps.empty() ? 0 : r.grasps.back(), campaign.out_dir.c_str());
  if (result.history.fault_total > 0 || result.history.node_reboots > 0)
    std::fprintf(stderr, "curio-controller: %s\n", note.c_str());
  print_verdict(r);
  if (!result.inexact.empty()) {
    std::fprintf(stderr,
                 "curio-controller: results written but marked (summary.json \"bus\"): a fault "
                 "may have changed them; exit status 3\n");
    return 3;
  }
  return 0;
}

}  // namespace curio::app::host
