#include "firmware/app/host/bus_run.hpp"

#include <chrono>
#include <memory>

#include "explore/explorer.hpp"
#include "explore/module_layouts.hpp"
#include "host_tools/lab/checkpoints.hpp"
#include "host_tools/lab/controllability.hpp"
#include "host_tools/lab/exploration_ratio.hpp"
#include "host_tools/lab/representations.hpp"
#include "nn/encoder.hpp"

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
  auto controller = std::make_unique<Controller>();
  if (const AppStatus s = controller->init(bus, explorer.get(), options.controller, encoder.get());
      s != AppStatus::kOk) {
    r.error = std::string("controller init failed: ") + to_string(s);
    return out;
  }
  controller->set_cycle_probe(options.probe);
  if (const AppStatus s = controller->start_arm(); s != AppStatus::kOk) {
    r.error = std::string("the arm did not come up: ") + to_string(s) + " (" +
              fault_summary(controller->counters()) +
              "); is `curio-sim serve` running on this bus?";
    out.counters = controller->counters();
    return out;
  }
  out.physics = controller->query_physics();
  if (out.physics == 0) r.spec.physics = sim::Physics::kKinematic;
  if (out.physics == 1) r.spec.physics = sim::Physics::kOde;

  r.module_names = lab::module_names(spec.algorithm, rep ? rep->kl_order.data() : nullptr);
  if (rep) {
    const int g = spec.algorithm.group_size;
    for (int m = 0; m < kLatentDim / g; ++m) {
      std::vector<int> latents;
      for (int j = 0; j < g; ++j) latents.push_back(rep->kl_order[static_cast<size_t>(m * g + j)]);
      r.module_latents.push_back(latents);
    }
  }
  const int total = explorer->total_episodes();
  r.checkpoints = lab::curve_checkpoints(total);
  r.module_choices.assign(static_cast<size_t>(explorer->n_modules()), 0);
  r.final_ball.reserve(static_cast<size_t>(total));

  // The same bookkeeping as lab::run_exploration, fed from the controller's episode records.
  lab::ExplorationRatio metric;
  int grasps = 0;
  size_t next_checkpoint = 0;
  auto record_checkpoints = [&](int n) {
    while (next_checkpoint < r.checkpoints.size() && r.checkpoints[next_checkpoint] == n) {
      r.ratio.push_back(metric.ratio());
      r.grasps.push_back(grasps);
      ++next_checkpoint;
    }
  };
  auto record_interest = [&](int n) {
    if (explorer->n_modules() == 0 || n % spec.interest_every != 0) return;
    std::vector<float> row(static_cast<size_t>(explorer->n_modules()));
    for (int k = 0; k < explorer->n_modules(); ++k)
      row[static_cast<size_t>(k)] = explorer->interest(k);
    r.interest_episodes.push_back(n);
    r.interest.push_back(std::move(row));
  };
  record_checkpoints(0);
  record_interest(0);

  const auto t0 = clock::now();
  auto last_progress = t0;
  while (!explorer->done()) {
    const AppStatus s = controller->run_episode();
    if (s != AppStatus::kOk) {
      r.error = "episode " + std::to_string(explorer->episode()) + ": " + to_string(s) + " (" +
                fault_summary(controller->counters()) + ")";
      break;
    }
    const EpisodeRecord& e = controller->last_episode();
    if (e.exploit) {
      ++r.module_choices[static_cast<size_t>(e.module)];
      r.exploits.push_back({explorer->episode(), e.module, e.progress});
    }
    r.final_ball.push_back({e.ball[0], e.ball[1]});
    metric.add(e.ball[0], e.ball[1]);
    if (e.grasped) ++grasps;
    const int n = explorer->episode();
    record_checkpoints(n);
    record_interest(n);
    const auto now = clock::now();
    if (options.progress &&
        (std::chrono::duration<double>(now - last_progress).count() >= options.progress_every_s ||
         n == total)) {
      const double dt = std::chrono::duration<double>(now - t0).count();
      std::fprintf(options.progress,
                   "curio-controller: %d/%d episodes, ratio %.3f, %llu grasps, %.0f episodes/s, "
                   "%llu faults, %llu replays\n",
                   n, total, metric.ratio(), static_cast<unsigned long long>(grasps),
                   dt > 0 ? n / dt : 0.0,
                   static_cast<unsigned long long>(controller->counters().fault_total),
                   static_cast<unsigned long long>(controller->counters().replays));
      std::fflush(options.progress);
      last_progress = now;
    }
  }
  out.seconds = std::chrono::duration<double>(clock::now() - t0).count();
  r.seconds = out.seconds;
  if (r.error.empty())
    r.verdicts =
        lab::classify_modules(r.exploits, r.interest, r.interest_episodes, spec.n_bootstrap, total);
  controller->stop_arm();
  out.counters = controller->counters();
  out.image = controller->image_counters();
  out.frames_sent = out.counters.frames_sent;
  out.frames_received = out.counters.frames_received;
  if (on_finish) on_finish(*explorer);
  return out;
}

}  // namespace curio::app::host
