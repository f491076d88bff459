// Controllable-feature discovery (paper §4.3, SPEC §4's last claim): from a run's learning
// progress alone, decide which goal modules the agent controls.
//
// Statistic. For each module k, over the second half of its exploit episodes (after the
// bootstrap), take the learning progress p = c − c_old of every exploit (SPEC §2.5) and the
// smoothed interest |cp| sampled along the run:
//   t_k = mean(p) / (std(p) / √n)            is the mean progress significantly above 0?
//   relative_interest_k = mean |cp_k| / max_j mean |cp_j|
// A module is controllable iff t_k ≥ 3 and relative_interest_k ≥ 0.1.
// Why: for an outcome the arm cannot influence (the distractor's random walk, a collapsed
// latent) the old and the new outcome are exchangeable, so p has zero mean; for a
// controllable outcome the nearest-neighbour inverse model keeps getting closer to its goals
// and p is almost never negative. The relative floor drops modules whose progress is real
// but negligible next to the best module's. Both tests are scale-free (no goal-space units).
#pragma once
#include <string>
#include <vector>

namespace curio::lab {

struct ControllabilityThresholds {
  double min_t = 3.0;
  double min_relative_interest = 0.1;
};

// One exploit's learning progress.
struct ProgressSample {
  int episode = 0;
  int module = 0;
  float progress = 0.0f;
};

struct ModuleVerdict {
  int exploits = 0;          // exploits in the judged window
  double mean_progress = 0.0;
  double t = 0.0;
  double mean_interest = 0.0;
  double relative_interest = 0.0;
  bool controllable = false;
};

// exploits: every exploit's progress; interest[s][k]: |cp| of module k at sample s taken at
// episode sample_episodes[s]. Only episodes in the second half of (first_episode, last
// episode] count. Empty result when there are no modules.
std::vector<ModuleVerdict> classify_modules(const std::vector<ProgressSample>& exploits,
                                            const std::vector<std::vector<float>>& interest,
                                            const std::vector<int>& sample_episodes,
                                            int first_episode, int last_episode,
                                            const ControllabilityThresholds& t = {});

// Latents named by the controllable modules (module k covers latents module_latents[k]).
std::vector<int> controllable_latents(const std::vector<ModuleVerdict>& verdicts,
                                      const std::vector<std::vector<int>>& module_latents);

}  // namespace curio::lab
