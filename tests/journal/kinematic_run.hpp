// The kinematic arm in-process with the explorer and a journal, composed as the controller
// composes them (propose, roll out, observe, append), and curio-lab's live run to compare with.
#pragma once
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <memory>

#include "firmware/app/episode_outcome.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/explore/fnv1a.hpp"
#include "firmware/journal/journal.hpp"
#include "host_tools/experiment/algorithms.hpp"
#include "host_tools/experiment/simulated_run.hpp"
#include "sim/world.hpp"
#include "tests/journal/journal_test_util.hpp"

namespace curio::journal::test {

inline constexpr int kBootstrap = 50;
inline constexpr int kEpisodes = 250;  // 300 episodes in all

inline lab::RunSpec spec_of(const char* algo, uint64_t seed) {
  lab::RunSpec s;
  s.algorithm = *lab::find_algorithm(algo);
  s.physics = sim::Physics::kKinematic;
  s.explorer.seed = seed;
  s.explorer.n_bootstrap = kBootstrap;
  s.explorer.n_episodes = kEpisodes;
  s.explorer.competence_cap = static_cast<float>(s.algorithm.default_competence_clip);
  return s;
}

// The archive (θ and outcomes) and every module's final interest, as the QEMU images print it.
inline uint32_t checksum(const Explorer& e) {
  Fnv1a f;
  f.add_archive(e.archive());
  for (int k = 0; k < e.n_modules(); ++k) f.add_float(e.interest(k));
  return f.h;
}

inline uint32_t live_checksum(const lab::RunSpec& spec) {
  uint32_t c = 0;
  const lab::RunResult r = lab::run_exploration(spec, nullptr, [&](const Explorer& e) {
    EXPECT_TRUE(e.done());
    c = checksum(e);
  });
  EXPECT_EQ(r.error, "");
  return c;
}

inline RunIdentity identity(const lab::RunSpec& spec) {
  RunIdentity id = test_identity(spec.explorer.seed);
  std::strncpy(id.algorithm_name, spec.algorithm.name.c_str(), kAlgorithmNameBytes - 1);
  return id;
}

// The explorer, the arm and the journal, as the controller composes them (one process).
struct ArmRun {
  explicit ArmRun(const lab::RunSpec& s) : spec(s), explorer(std::make_unique<Explorer>()) {
    ExplorerConfig config;
    EXPECT_EQ(lab::make_explorer_config(spec, &config), Status::kOk);
    EXPECT_EQ(explorer->init(config), Status::kOk);
    world = sim::make_world(spec.physics, spec.world, lab::world_seed(spec.explorer.seed));
  }
  // Runs episodes up to `until` (or the end), journaling each after observe().
  void run_until(int until, JournalWriter* w) {
    run_until(until,
              [w](const EpisodeEntry& e) { return !w || w->append(e) == JournalStatus::kOk; });
  }
  // `sink` sees each episode's entry after observe(); false stops the run (a failed append).
  void run_until(int until, const std::function<bool(const EpisodeEntry&)>& sink) {
    float theta[kThetaDim];
    while (!explorer->done() && explorer->episode() < until) {
      ASSERT_EQ(explorer->propose(theta), Status::kOk);
      EpisodeEntry e;
      e.episode = static_cast<uint32_t>(explorer->episode());
      e.kind = static_cast<uint8_t>(explorer->kind());
      e.module = static_cast<int8_t>(explorer->module());
      e.exploit = explorer->kind() == EpisodeKind::kExploit && explorer->module() >= 0;
      const sim::SceneState s = world->rollout_joint_targets(theta);
      e.outcome_dim = static_cast<uint8_t>(explorer->config().outcome_dim);
      const app::FinalPositions p{s.ball.x, s.ball.y, s.distractor.x, s.distractor.y};
      ASSERT_TRUE(app::episode_outcome(p, nullptr, nullptr, e.outcome));
      ASSERT_EQ(explorer->observe(e.outcome), Status::kOk);
      e.progress = explorer->last_progress();
      e.grasped = s.grasped;
      e.ball[0] = static_cast<float>(s.ball.x);
      e.ball[1] = static_cast<float>(s.ball.y);
      e.distractor[0] = static_cast<float>(s.distractor.x);
      e.distractor[1] = static_cast<float>(s.distractor.y);
      e.attempts = 1;
      ASSERT_TRUE(sink(e)) << "journaling episode " << e.episode;
    }
  }
  lab::RunSpec spec;
  std::unique_ptr<Explorer> explorer;
  std::unique_ptr<sim::World> world;
};

}  // namespace curio::journal::test
