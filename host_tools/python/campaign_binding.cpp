// Campaigns in-process (algorithms × seeds × σ on threads, the GIL released): each run is
// curio-lab's run_exploration of the RunSpec curio-lab expands; and the metric helpers
// (exploration ratio, checkpoints).
#include <atomic>
#include <chrono>
#include <thread>

#include "host_tools/experiment/campaign_config.hpp"
#include "host_tools/experiment/checkpoints.hpp"
#include "host_tools/experiment/exploration_ratio.hpp"
#include "host_tools/experiment/simulated_run.hpp"
#include "host_tools/python/bindings.hpp"

namespace curio::python {

namespace {

template <typename T>
py::array_t<T> to_array(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict run_dict(const lab::RunResult& r) {
  py::dict d;
  d["algorithm"] = r.spec.algorithm.name;
  d["seed"] = r.spec.explorer.seed;
  d["sigma"] = r.spec.explorer.sigma;
  d["error"] = r.error;
  d["checkpoints"] = to_array(r.checkpoints);
  d["ratio"] = to_array(r.ratio);
  d["grasps"] = to_array(r.grasps);
  d["module_names"] = r.module_names;
  d["module_choices"] = to_array(r.module_choices);
  const auto k = static_cast<py::ssize_t>(r.module_names.size());
  py::array_t<float> interest({static_cast<py::ssize_t>(r.interest.size()), k});
  for (size_t s = 0; s < r.interest.size(); ++s)
    for (py::ssize_t j = 0; j < k && j < static_cast<py::ssize_t>(r.interest[s].size()); ++j)
      interest.mutable_at(static_cast<py::ssize_t>(s), j) = r.interest[s][static_cast<size_t>(j)];
  d["interest"] = interest;
  d["interest_episodes"] = to_array(r.interest_episodes);
  py::array_t<bool> controllable(static_cast<py::ssize_t>(r.verdicts.size()));
  py::array_t<double> t(static_cast<py::ssize_t>(r.verdicts.size()));
  for (size_t j = 0; j < r.verdicts.size(); ++j) {
    controllable.mutable_at(static_cast<py::ssize_t>(j)) = r.verdicts[j].controllable;
    t.mutable_at(static_cast<py::ssize_t>(j)) = r.verdicts[j].t;
  }
  d["controllable"] = controllable;
  d["t"] = t;
  d["verdict"] = r.error.empty() && !r.verdicts.empty() ? lab::verdict_text(r) : std::string();
  d["expected_verdict"] = r.error.empty() ? lab::expected_verdict(r) : std::string();
  d["seconds"] = r.seconds;
  d["cpu_seconds"] = r.cpu_seconds;
  return d;
}

py::list run_campaign(const std::vector<std::string>& algorithms, const std::vector<uint64_t>& seeds,
                      int episodes, const std::vector<double>& sigmas, const std::string& physics,
                      int bootstrap, double competence_clip, double window, double epsilon,
                      const std::string& tie_rule, const std::string& competence_measure,
                      const std::string& explore, int threads) {
  lab::CampaignConfig c;
  c.algorithms = algorithms;
  c.seeds = seeds;
  c.sigmas = sigmas;
  c.episodes = episodes;
  if (!sim::parse_physics(physics, &c.physics))
    value_error("physics", "expected 'kinematic' or 'ode', got '" + physics + "'");
  c.bootstrap = bootstrap;
  c.competence_clip = competence_clip;
  c.window = window;
  c.epsilon = epsilon;
  const auto tie = lab::parse_tie_rule(tie_rule);
  if (!tie) value_error("tie_rule", "expected 'latest' or 'earliest', got '" + tie_rule + "'");
  c.tie_rule = *tie;
  const auto measure = lab::parse_competence_measure(competence_measure);
  if (!measure) value_error("competence_measure", "expected 'clip' or 'scale', got '" + competence_measure + "'");
  c.competence_measure = *measure;
  c.explore = explore;
  if (threads < 0) value_error("threads", "expected a number >= 0 (0: all cores)");
  c.threads = threads;
  const auto problems = lab::validate_campaign(c);
  if (!problems.empty()) {
    std::string text;
    for (const auto& p : problems) text += (text.empty() ? "" : "; ") + p;
    value_error("campaign", text);
  }
  const std::vector<lab::RunSpec> runs = lab::expand_runs(c);
  std::vector<lab::RunResult> results(runs.size());
  int n_threads = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  n_threads = std::max(1, std::min<int>(n_threads, static_cast<int>(runs.size())));
  std::atomic<size_t> next{0};
  std::atomic<int> finished{0};
  std::atomic<bool> stop{false};
  {
    py::gil_scoped_release release;
    std::vector<std::thread> pool;
    for (int t = 0; t < n_threads; ++t)
      pool.emplace_back([&] {
        for (size_t i = next.fetch_add(1); i < runs.size(); i = next.fetch_add(1)) {
          if (stop.load()) break;
          lab::RunHooks hooks;
          hooks.stop = &stop;
          results[i] = lab::run_exploration(runs[i], nullptr, {}, hooks);
        }
        finished.fetch_add(1);
      });
    // Ctrl-C: the runs in flight stop before their next episode and KeyboardInterrupt is raised.
    bool interrupted = false;
    while (finished.load() < n_threads) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      py::gil_scoped_acquire acquire;
      if (!interrupted && PyErr_CheckSignals() != 0) {
        interrupted = true;
        stop.store(true);
      }
    }
    for (auto& th : pool) th.join();
    if (interrupted) {
      py::gil_scoped_acquire acquire;
      throw py::error_already_set();
    }
  }
  py::list out;
  for (const auto& r : results) out.append(run_dict(r));
  return out;
}

}  // namespace

void bind_campaign(py::module_& m) {
  m.def("_run_campaign", &run_campaign, py::arg("algorithms"), py::arg("seeds"),
        py::arg("episodes"), py::arg("sigmas"), py::arg("physics"), py::arg("bootstrap"),
        py::arg("competence_clip"), py::arg("window"), py::arg("epsilon"), py::arg("tie_rule"),
        py::arg("competence_measure"), py::arg("explore"), py::arg("threads"));
  m.def(
      "_canonical_algorithm",
      [](const std::string& name) -> py::object {
        const auto a = lab::find_algorithm(name);
        if (!a) return py::none();
        return py::str(a->name);
      },
      py::arg("name"));
  m.def(
      "checkpoints",
      [](int total_episodes) {
        if (total_episodes < 0) value_error("total_episodes", "expected a number >= 0");
        return to_array(lab::curve_checkpoints(total_episodes));
      },
      py::arg("total_episodes"),
      "Episode counts at which curio-lab records the ratio: SPEC §4's floor(i*10000/30), every "
      "100 episodes, and the total.");
  m.def(
      "exploration_ratio",
      [](const py::object& points, const py::object& checkpoints) -> py::object {
        const auto p = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
        if (!p || p.ndim() != 2 || p.shape(1) != 2)
          value_error("points", "expected an (N, 2) array of final (x, y) positions");
        lab::ExplorationRatio metric;
        if (checkpoints.is_none()) {
          for (py::ssize_t i = 0; i < p.shape(0); ++i) metric.add(p.at(i, 0), p.at(i, 1));
          return py::float_(metric.ratio());
        }
        const auto c = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(checkpoints);
        if (!c || c.ndim() != 1) value_error("checkpoints", "expected a 1-D array of episode counts");
        py::array_t<double> out(c.shape(0));
        py::ssize_t added = 0;
        for (py::ssize_t k = 0; k < c.shape(0); ++k) {
          const int64_t n = c.at(k);
          if (n < added || n > p.shape(0))
            value_error("checkpoints", "expected increasing counts in 0.." + std::to_string(p.shape(0)));
          for (; added < n; ++added) metric.add(p.at(added, 0), p.at(added, 1));
          out.mutable_at(k) = metric.ratio();
        }
        return out;
      },
      py::arg("points"), py::arg("checkpoints") = py::none(),
      "SPEC §4's exploration ratio: the share of the 900 cells of a 30x30 grid over [-1, 1]^2 "
      "holding at least one of the (N, 2) points. With checkpoints (increasing episode counts), "
      "the ratio after the first n points for each n.");
}

}  // namespace curio::python
