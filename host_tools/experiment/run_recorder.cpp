#include "host_tools/experiment/run_recorder.hpp"

#include "firmware/explore/module_layouts.hpp"
#include "host_tools/experiment/checkpoints.hpp"

namespace curio::lab {

RunRecorder::RunRecorder(const Explorer& explorer, const Representation* rep, RunResult* result)
    : explorer_(explorer), r_(*result) {
  const AlgorithmSpec& algo = r_.spec.algorithm;
  r_.module_names = module_names(algo, rep ? rep->kl_order.data() : nullptr);
  if (rep) {
    const int g = algo.group_size;
    for (int m = 0; m < kLatentDim / g; ++m) {
      std::vector<int> latents;
      for (int j = 0; j < g; ++j) latents.push_back(rep->kl_order[static_cast<size_t>(m * g + j)]);
      r_.module_latents.push_back(latents);
    }
  }
  const int total = explorer_.total_episodes();
  r_.checkpoints = curve_checkpoints(total);
  r_.ratio.reserve(r_.checkpoints.size());
  r_.grasps.reserve(r_.checkpoints.size());
  r_.module_choices.assign(static_cast<size_t>(explorer_.n_modules()), 0);
  // Everything recorded per episode is sized (and its memory touched) here, so that a run's
  // resident size stays flat after start-up: curio-controller's grew about 13 bytes an
  // episode while the interest rows, exploits and final positions were appended.
  const auto touch = [](auto& v, size_t n) {  // capacity n, its pages written once
    if (!v.empty()) return;
    v.resize(n);
    v.clear();
  };
  const auto episodes = static_cast<size_t>(total) + 1;
  touch(r_.final_ball, episodes);
  touch(r_.exploits, episodes);
  if (explorer_.n_modules() > 0) {
    const size_t rows = episodes / static_cast<size_t>(r_.spec.interest_every) + 1;
    touch(r_.interest_episodes, rows);
    touch(r_.interest, rows);
    spare_rows_.assign(rows, std::vector<float>(static_cast<size_t>(explorer_.n_modules())));
  }
  record_checkpoints(0);
  record_interest(0);
}

void RunRecorder::record_episode(bool exploit, int module, float progress, float ball_x,
                                 float ball_y, bool grasped) {
  const int n = explorer_.episode();
  if (exploit && module >= 0) {
    ++r_.module_choices[static_cast<size_t>(module)];
    r_.exploits.push_back({n, module, progress});
  }
  r_.final_ball.push_back({ball_x, ball_y});
  metric_.add(ball_x, ball_y);
  if (grasped) ++grasps_;
  record_checkpoints(n);
  record_interest(n);
}

void RunRecorder::finish() {
  r_.verdicts = classify_modules(r_.exploits, r_.interest, r_.interest_episodes,
                                 r_.spec.explorer.n_bootstrap, explorer_.total_episodes());
}

void RunRecorder::record_checkpoints(int n) {
  while (next_checkpoint_ < r_.checkpoints.size() && r_.checkpoints[next_checkpoint_] == n) {
    r_.ratio.push_back(metric_.ratio());
    r_.grasps.push_back(grasps_);
    ++next_checkpoint_;
  }
}

void RunRecorder::record_interest(int n) {
  if (explorer_.n_modules() == 0 || n % r_.spec.interest_every != 0) return;
  std::vector<float> row;  // one of the rows sized at start, while they last
  if (!spare_rows_.empty()) {
    row = std::move(spare_rows_.back());
    spare_rows_.pop_back();
  }
  row.resize(static_cast<size_t>(explorer_.n_modules()));
  for (int k = 0; k < explorer_.n_modules(); ++k) row[static_cast<size_t>(k)] = explorer_.interest(k);
  r_.interest_episodes.push_back(n);
  r_.interest.push_back(std::move(row));
}

}  // namespace curio::lab
