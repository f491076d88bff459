// What a run records, episode by episode, however its episodes are executed (in-process by
// curio-lab, or over the bus by curio-controller): one implementation, so both write the
// same result files for the same archive.
#pragma once
#include <vector>

#include "firmware/explore/explorer.hpp"
#include "host_tools/experiment/exploration_ratio.hpp"
#include "host_tools/experiment/representations.hpp"
#include "host_tools/experiment/run.hpp"

namespace curio::lab {

class RunRecorder {
 public:
  // Sets the run's module names and latents and its checkpoints, and records episode 0.
  // `explorer` must be initialised and outlive the recorder; `rep` is null for EFR and RPE.
  RunRecorder(const Explorer& explorer, const Representation* rep, RunResult* result);

  // After explorer.observe() of each episode: whether it was an exploit (of `module`, with
  // learning progress `progress`), the final ball position as received, and the grasp.
  void record_episode(bool exploit, int module, float progress, float ball_x, float ball_y,
                      bool grasped);

  // Controllable-feature verdicts; call once the run is complete.
  void finish();

  double ratio() const { return metric_.ratio(); }
  int grasps() const { return grasps_; }

 private:
  void record_checkpoints(int episodes);
  void record_interest(int episodes);

  const Explorer& explorer_;
  RunResult& r_;
  ExplorationRatio metric_;
  int grasps_ = 0;
  size_t next_checkpoint_ = 0;
  std::vector<std::vector<float>> spare_rows_;  // interest rows sized at start (record_interest)
};

}  // namespace curio::lab
