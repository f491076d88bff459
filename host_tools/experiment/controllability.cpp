#include "host_tools/experiment/controllability.hpp"

#include <algorithm>
#include <cmath>

namespace curio::lab {

std::vector<ModuleVerdict> classify_modules(const std::vector<ProgressSample>& exploits,
                                            const std::vector<std::vector<float>>& interest,
                                            const std::vector<int>& sample_episodes,
                                            int first_episode, int last_episode,
                                            const ControllabilityThresholds& t) {
  if (interest.empty() || interest.front().empty()) return {};
  const int window_start = first_episode + (last_episode - first_episode) / 2;
  const size_t n_modules = interest.front().size();
  std::vector<ModuleVerdict> v(n_modules);
  std::vector<double> sum(n_modules, 0.0), sum_sq(n_modules, 0.0);
  for (const auto& e : exploits) {
    if (e.episode <= window_start || e.module < 0 || size_t(e.module) >= n_modules) continue;
    const auto k = static_cast<size_t>(e.module);
    ++v[k].exploits;
    sum[k] += e.progress;
    sum_sq[k] += double(e.progress) * e.progress;
  }
  std::vector<double> mean_interest(n_modules, 0.0);
  int samples = 0;
  for (size_t s = 0; s < interest.size() && s < sample_episodes.size(); ++s) {
    if (sample_episodes[s] <= window_start) continue;
    ++samples;
    for (size_t k = 0; k < n_modules; ++k) mean_interest[k] += std::fabs(interest[s][k]);
  }
  double best = 0.0;
  for (size_t k = 0; k < n_modules; ++k) {
    if (samples > 0) mean_interest[k] /= samples;
    best = std::max(best, mean_interest[k]);
  }
  for (size_t k = 0; k < n_modules; ++k) {
    auto& m = v[k];
    m.mean_interest = mean_interest[k];
    m.relative_interest = best > 0.0 ? mean_interest[k] / best : 0.0;
    if (m.exploits >= 2) {
      const double n = m.exploits;
      m.mean_progress = sum[k] / n;
      const double var = std::max(0.0, (sum_sq[k] - n * m.mean_progress * m.mean_progress) / (n - 1));
      m.t = var > 0.0 ? m.mean_progress / std::sqrt(var / n) : (m.mean_progress > 0 ? 1e9 : 0.0);
    }
    m.controllable = m.t >= t.min_t && m.relative_interest >= t.min_relative_interest;
  }
  return v;
}

std::vector<int> controllable_latents(const std::vector<ModuleVerdict>& verdicts,
                                      const std::vector<std::vector<int>>& module_latents) {
  std::vector<int> latents;
  for (size_t k = 0; k < verdicts.size() && k < module_latents.size(); ++k)
    if (verdicts[k].controllable)
      latents.insert(latents.end(), module_latents[k].begin(), module_latents[k].end());
  std::sort(latents.begin(), latents.end());
  return latents;
}

}  // namespace curio::lab
