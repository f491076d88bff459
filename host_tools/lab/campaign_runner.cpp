#include "host_tools/lab/campaign_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

#include "firmware/explore/explorer.hpp"
#include "firmware/explore/fnv1a.hpp"

namespace curio::lab {

std::vector<RunResult> run_campaign(const CampaignConfig& c, double* wall_seconds) {
  return run_some(c, expand_runs(c), wall_seconds);
}

std::vector<RunResult> run_some(const CampaignConfig& c, const std::vector<RunSpec>& runs,
                                double* wall_seconds,
                                const std::function<void(size_t, RunResult&)>& on_done,
                                const std::atomic<bool>* stop,
                                const std::function<RunHooks(size_t)>& hooks_for) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<RunResult> results(runs.size());
  int threads = c.threads > 0 ? c.threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::clamp(threads, 1, static_cast<int>(std::max<size_t>(runs.size(), 1)));

  int64_t total_episodes = 0;
  for (const auto& r : runs) total_episodes += r.explorer.n_bootstrap + r.explorer.n_episodes;
  std::atomic<int64_t> episodes_done{0};
  std::atomic<size_t> next{0};
  std::atomic<int> runs_done{0};
  std::mutex print_mutex;

  if (!c.quiet)
    std::fprintf(stderr, "curio-lab: %zu runs (%lld episodes, %s physics) on %d threads\n",
                 runs.size(), static_cast<long long>(total_episodes), sim::physics_name(c.physics),
                 threads);

  auto worker = [&] {
    for (size_t i = next.fetch_add(1); i < runs.size(); i = next.fetch_add(1)) {
      if (stop && stop->load()) {
        results[i].spec = runs[i];
        results[i].error = kNotStarted;
        continue;
      }
      RunHooks hooks = hooks_for ? hooks_for(i) : RunHooks{};
      hooks.stop = stop;
      uint32_t checksum = 0;
      const auto archive_checksum = [&checksum](const Explorer& explorer) {
        Fnv1a f;
        f.add_archive(explorer.archive());
        checksum = f.h;
      };
      results[i] = run_exploration(runs[i], &episodes_done,
                                   c.print_checksum ? std::function<void(const Explorer&)>(archive_checksum)
                                                    : std::function<void(const Explorer&)>(),
                                   hooks);
      if (c.print_checksum && results[i].error.empty()) {
        std::lock_guard lock(print_mutex);
        std::fprintf(stderr, "curio-lab: %s seed %llu σ=%g: archive checksum 0x%08x (%d episodes)\n",
                     runs[i].algorithm.name.c_str(),
                     static_cast<unsigned long long>(runs[i].explorer.seed), runs[i].explorer.sigma,
                     static_cast<unsigned>(checksum),
                     runs[i].explorer.n_bootstrap + runs[i].explorer.n_episodes);
      }
      // The progress line is taken before on_done may drop what it has written.
      const RunResult& r = results[i];
      const double last_ratio = r.ratio.empty() ? 0.0 : r.ratio.back();
      const int last_grasps = r.grasps.empty() ? 0 : r.grasps.back();
      const std::string verdict =
          r.error.empty() && r.verdicts.size() > 1 ? "  controllable: " + verdict_text(r) : "";
      if (on_done) on_done(i, results[i]);
      if (stopped_early(r)) continue;  // not a finished run: no progress line
      const int done = runs_done.fetch_add(1) + 1;
      if (c.quiet) continue;
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double frac =
          double(episodes_done.load()) / double(std::max<int64_t>(total_episodes, 1));
      std::lock_guard lock(print_mutex);
      if (!r.error.empty()) {
        std::fprintf(stderr, "[%d/%zu] %s seed %llu σ=%g FAILED: %s\n", done, runs.size(),
                     r.spec.algorithm.name.c_str(),
                     static_cast<unsigned long long>(r.spec.explorer.seed), r.spec.explorer.sigma,
                     r.error.c_str());
      } else {
        std::fprintf(stderr,
                     "[%d/%zu] %-8s seed %-3llu σ=%-5g ratio %.3f  grasps %5d  %.2fs   "
                     "(%.0f%%, %.0fs elapsed, ETA %.0fs)%s\n",
                     done, runs.size(), r.spec.algorithm.name.c_str(),
                     static_cast<unsigned long long>(r.spec.explorer.seed), r.spec.explorer.sigma,
                     last_ratio, last_grasps, r.seconds, 100.0 * frac, elapsed,
                     frac > 0 ? elapsed / frac - elapsed : 0.0, verdict.c_str());
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  *wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return results;
}

}  // namespace curio::lab
