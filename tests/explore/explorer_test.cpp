#include "firmware/explore/explorer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "firmware/explore/module_layouts.hpp"
#include "firmware/explore/nearest_neighbour.hpp"
#include "firmware/explore/schedule.hpp"
#include "tests/explore/toy_environment.hpp"

namespace curio {
namespace {

using test::toy_outcome;

ExplorerConfig small_config(Algorithm algorithm, uint64_t seed) {
  ExplorerConfig c;
  set_efr_modules(c, algorithm);
  c.n_bootstrap = 100;
  c.n_episodes = 1000;
  c.seed = seed;
  return c;
}

// Runs to completion on the toy environment.
void run(Explorer& e) {
  float theta[kThetaDim];
  float outcome[4];
  while (!e.done()) {
    ASSERT_EQ(e.propose(theta), Status::kOk);
    toy_outcome(theta, outcome);
    ASSERT_EQ(e.observe(outcome), Status::kOk);
  }
}

bool same_archive(const Archive& a, const Archive& b) {
  if (a.size() != b.size() || a.outcome_dim() != b.outcome_dim()) return false;
  float ta[kThetaDim], tb[kThetaDim];
  for (int i = 0; i < a.size(); ++i) {
    a.theta(i, ta);
    b.theta(i, tb);
    if (std::memcmp(ta, tb, sizeof ta) != 0) return false;
    for (int d = 0; d < a.outcome_dim(); ++d) {
      const float x = a.outcome(i, d), y = b.outcome(i, d);
      if (std::memcmp(&x, &y, sizeof x) != 0) return false;
    }
  }
  return true;
}

// Runs `run` (which takes a std::unique_ptr<Explorer>&) on two fresh explorers and expects
// their archives to be the same bit for bit; returns the first for further checks.
template <class Run>
std::unique_ptr<Explorer> expect_run_repeats_bit_for_bit(Run run) {
  auto a = std::make_unique<Explorer>();
  auto b = std::make_unique<Explorer>();
  run(a);
  run(b);
  EXPECT_TRUE(same_archive(a->archive(), b->archive()));
  return a;
}

TEST(Explorer, SameSeedGivesTheSameArchiveBitForBit) {
  for (const Algorithm alg : {Algorithm::kRpe, Algorithm::kRge, Algorithm::kMge}) {
    auto a = std::make_unique<Explorer>();
    auto b = std::make_unique<Explorer>();
    ASSERT_EQ(a->init(small_config(alg, 11)), Status::kOk);
    ASSERT_EQ(b->init(small_config(alg, 11)), Status::kOk);
    run(*a);
    run(*b);
    EXPECT_EQ(a->archive().size(), 1100);
    EXPECT_TRUE(same_archive(a->archive(), b->archive()));
    for (int k = 0; k < a->n_modules(); ++k) EXPECT_EQ(a->interest(k), b->interest(k));

    // Re-init of a used explorer restarts the same run.
    ASSERT_EQ(b->init(small_config(alg, 11)), Status::kOk);
    EXPECT_EQ(b->archive().size(), 0);
    run(*b);
    EXPECT_TRUE(same_archive(a->archive(), b->archive()));

    ASSERT_EQ(b->init(small_config(alg, 12)), Status::kOk);
    run(*b);
    EXPECT_FALSE(same_archive(a->archive(), b->archive()));
  }
}

TEST(Explorer, FollowsTheStepSchedule) {
  auto e = std::make_unique<Explorer>();
  ExplorerConfig c = small_config(Algorithm::kMge, 3);
  c.sigma = 0.05f;
  ASSERT_EQ(e->init(c), Status::kOk);
  EXPECT_EQ(e->total_episodes(), 1100);
  float theta[kThetaDim], outcome[4];
  int explore_source = -1;
  int nn_explores = 0, nn_exploits = 0;
  for (int ep = 0; ep < 1100; ++ep) {
    ASSERT_EQ(e->episode(), ep);
    ASSERT_EQ(e->propose(theta), Status::kOk);
    const EpisodeKind kind = e->kind();
    if (ep < 100) {
      EXPECT_EQ(kind, EpisodeKind::kBootstrap);
      EXPECT_EQ(e->module(), -1);
    } else if ((ep - 100) % 5 < 4) {
      ASSERT_EQ(kind, EpisodeKind::kExplore) << ep;
      if ((ep - 100) % 5 == 0) explore_source = e->source_episode();
      EXPECT_EQ(e->source_episode(), explore_source) << "one θ_nn per step, episode " << ep;
      if (e->source_episode() >= 0) {
        ++nn_explores;
        float base[kThetaDim];
        e->archive().theta(e->source_episode(), base);
        bool moved = false;
        for (int i = 0; i < kThetaDim; ++i) {
          ASSERT_GE(theta[i], -1.0f);
          ASSERT_LE(theta[i], 1.0f);
          ASSERT_LE(std::fabs(theta[i] - base[i]), 6 * c.sigma) << "noise is N(0, σ²)";
          moved = moved || theta[i] != base[i];
        }
        EXPECT_TRUE(moved);
      }
    } else {
      ASSERT_EQ(kind, EpisodeKind::kExploit) << ep;
      const int src = e->source_episode();
      if (src >= 0) {
        ++nn_exploits;
        float source_theta[kThetaDim];
        e->archive().theta(src, source_theta);
        EXPECT_EQ(std::memcmp(theta, source_theta, sizeof theta), 0);
        // θ_nn is the nearest module outcome in the archive as it is now (explores included).
        const GoalModule& m = e->goal_module(e->module());
        EXPECT_EQ(src, nearest_neighbour(e->archive(), m.dims, m.n_dims, e->goal()));
      }
    }
    toy_outcome(theta, outcome);
    ASSERT_EQ(e->observe(outcome), Status::kOk);
  }
  EXPECT_TRUE(e->done());
  EXPECT_EQ(e->kind(), EpisodeKind::kNone);
  EXPECT_EQ(e->propose(theta), Status::kDone);
  EXPECT_EQ(e->counters().steps, 200u);
  EXPECT_GT(nn_explores, 700);
  EXPECT_GT(nn_exploits, 170);
}

TEST(Explorer, OnlyExploitEpisodesUpdateInterest) {
  auto e = std::make_unique<Explorer>();
  ASSERT_EQ(e->init(small_config(Algorithm::kMge, 5)), Status::kOk);
  float theta[kThetaDim], outcome[4];
  int updates = 0;
  while (!e->done()) {
    const float before[2] = {e->interest(0), e->interest(1)};
    e->propose(theta);
    const EpisodeKind kind = e->kind();
    const int module = e->module();
    toy_outcome(theta, outcome);
    e->observe(outcome);
    for (int k = 0; k < 2; ++k) {
      if (kind != EpisodeKind::kExploit || k != module) {
        ASSERT_EQ(e->interest(k), before[k]) << "episode " << e->episode() - 1;
      }
    }
    if (kind == EpisodeKind::kExploit) ++updates;
  }
  EXPECT_EQ(updates, 200);
  EXPECT_EQ(e->interest_model().history().size(), 200);
}

TEST(Explorer, RandomThetaUntilTheModuleHasTwoDistinctOutcomes) {
  // Ball module {2,3} only; the first 50 bootstrap episodes never "grasp" (forced θ below),
  // so the module sees one outcome: every goal episode must fall back to a random θ.
  auto e = std::make_unique<Explorer>();
  ExplorerConfig c;
  c.algorithm = Algorithm::kRge;
  c.outcome_dim = 4;
  c.n_modules = 1;
  c.modules[0] = ModuleDims{2, {2, 3}};
  c.n_bootstrap = 50;
  c.n_episodes = 50;
  ASSERT_EQ(e->init(c), Status::kOk);
  float theta[kThetaDim];
  const float still[4] = {0.1f, 0.2f, 0.6f, 0.6f};
  for (int ep = 0; ep < 75; ++ep) {
    ASSERT_EQ(e->propose(theta), Status::kOk);
    if (ep >= 50) {
      EXPECT_EQ(e->source_episode(), -1) << ep;
    }
    ASSERT_EQ(e->observe(still), Status::kOk);
  }
  EXPECT_FALSE(e->module_has_two_outcomes(0));
  EXPECT_EQ(e->counters().random_fallbacks, 25u);
  EXPECT_EQ(e->counters().nn_queries, 0u);
  // Episode 75 (first explore of a step, still random) reaches a different ball outcome.
  ASSERT_EQ(e->propose(theta), Status::kOk);
  const float moved[4] = {0.1f, 0.2f, 0.3f, -0.4f};
  ASSERT_EQ(e->observe(moved), Status::kOk);
  EXPECT_TRUE(e->module_has_two_outcomes(0));
  // The step's explores keep the random θ decided at its start; its exploit queries the NN.
  for (int ep = 76; ep < 79; ++ep) {
    ASSERT_EQ(e->propose(theta), Status::kOk);
    EXPECT_EQ(e->source_episode(), -1);
    ASSERT_EQ(e->observe(still), Status::kOk);
  }
  ASSERT_EQ(e->propose(theta), Status::kOk);
  EXPECT_EQ(e->kind(), EpisodeKind::kExploit);
  EXPECT_GE(e->source_episode(), 0);
}

TEST(Explorer, ProposeIsIdempotentAndObserveChecksOrderAndValues) {
  auto e = std::make_unique<Explorer>();
  ASSERT_EQ(e->init(small_config(Algorithm::kMge, 9)), Status::kOk);
  float theta[kThetaDim], again[kThetaDim], outcome[4] = {};
  EXPECT_EQ(e->observe(outcome), Status::kNoPendingEpisode);
  EXPECT_EQ(e->counters().out_of_order, 1u);
  ASSERT_EQ(e->propose(theta), Status::kOk);
  ASSERT_EQ(e->propose(again), Status::kOk);
  EXPECT_EQ(std::memcmp(theta, again, sizeof theta), 0);
  EXPECT_EQ(e->counters().repeated_proposals, 1u);
  EXPECT_EQ(e->propose(nullptr), Status::kInvalidArgument);
  outcome[2] = NAN;
  EXPECT_EQ(e->observe(outcome), Status::kNonFiniteOutcome);
  outcome[2] = INFINITY;
  EXPECT_EQ(e->observe(outcome), Status::kNonFiniteOutcome);
  EXPECT_EQ(e->counters().non_finite_outcomes, 2u);
  EXPECT_EQ(e->archive().size(), 0);
  EXPECT_TRUE(e->pending());
  toy_outcome(theta, outcome);
  EXPECT_EQ(e->observe(outcome), Status::kOk);
  EXPECT_EQ(e->archive().size(), 1);
  float stored[kThetaDim];
  e->archive().theta(0, stored);
  EXPECT_EQ(std::memcmp(stored, theta, sizeof theta), 0);
}

TEST(Explorer, ArchiveRegeneratesEveryProposedThetaAtFullSize) {
  // 100 + 10,000 episodes: every archived θ, re-made from its recipe, is the proposed θ.
  auto e = std::make_unique<Explorer>();
  ExplorerConfig c = small_config(Algorithm::kMge, 21);
  c.n_episodes = 10000;
  ASSERT_EQ(e->init(c), Status::kOk);
  std::vector<float> proposed;
  float theta[kThetaDim], outcome[4];
  while (!e->done()) {
    ASSERT_EQ(e->propose(theta), Status::kOk);
    proposed.insert(proposed.end(), theta, theta + kThetaDim);
    toy_outcome(theta, outcome);
    ASSERT_EQ(e->observe(outcome), Status::kOk);
  }
  const Archive& a = e->archive();
  ASSERT_EQ(a.size(), 10100);
  int deepest_lineage = 0;
  for (int i = 0; i < a.size(); ++i) {
    a.theta(i, theta);
    ASSERT_EQ(std::memcmp(theta, &proposed[static_cast<size_t>(i) * kThetaDim], sizeof theta), 0)
        << "episode " << i;
    ASSERT_LE(a.depth(i), Archive::kPoolDepth);
    deepest_lineage = std::max(deepest_lineage, a.lineage_depth(i));
  }
  EXPECT_EQ(a.pool_overflows(), 0u);
  EXPECT_GT(deepest_lineage, Archive::kPoolDepth) << "the run must exercise the pool";
  EXPECT_GT(a.pooled(), 0);
}

TEST(Explorer, LatentModulesRunAndStayDeterministic) {
  const uint8_t kl_order[kLatentDim] = {2, 3, 0, 1, 4, 5, 6, 7, 8, 9};
  auto run_latent = [&](std::unique_ptr<Explorer>& e) {
    ExplorerConfig c;
    ASSERT_EQ(set_latent_modules(c, kl_order, 1), Status::kOk);
    c.n_bootstrap = 400;
    c.n_episodes = 500;
    c.seed = 77;
    ASSERT_EQ(e->init(c), Status::kOk);
    float theta[kThetaDim], outcome[kLatentDim];
    while (!e->done()) {
      ASSERT_EQ(e->propose(theta), Status::kOk);
      if (e->kind() == EpisodeKind::kExplore && e->goal_dim() > 0) {
        for (int j = 0; j < e->goal_dim(); ++j) {
          ASSERT_LE(std::fabs(e->goal()[j]), 2.5f);
        }
      }
      test::toy_latent_outcome(theta, outcome);
      ASSERT_EQ(e->observe(outcome), Status::kOk);
    }
  };
  EXPECT_EQ(expect_run_repeats_bit_for_bit(run_latent)->n_modules(), 10);
}

// Explorer::rebase (curio-online's retrain): the goal space changes between steps, the run
// does not. Steps `episodes` episodes of the latent toy run (outcomes from toy_latent_outcome,
// optionally mapped by `remap` before observe).
void step_latent(Explorer& e, int episodes) {
  float theta[kThetaDim], outcome[kLatentDim];
  for (int i = 0; i < episodes && !e.done(); ++i) {
    ASSERT_EQ(e.propose(theta), Status::kOk);
    test::toy_latent_outcome(theta, outcome);
    ASSERT_EQ(e.observe(outcome), Status::kOk);
  }
}

ExplorerConfig latent_config(const uint8_t kl_order[kLatentDim], int group_size) {
  ExplorerConfig c;
  EXPECT_EQ(set_latent_modules(c, kl_order, group_size), Status::kOk);
  c.n_bootstrap = 100;
  c.n_episodes = 400;
  c.seed = 5;
  return c;
}

// The archive re-encoded by a "retrained" representation: the latents permuted and scaled.
std::vector<float> reencoded(const Archive& a, float scale) {
  std::vector<float> out(static_cast<size_t>(a.size()) * kLatentDim);
  for (int i = 0; i < a.size(); ++i)
    for (int d = 0; d < kLatentDim; ++d)
      out[static_cast<size_t>(i) * kLatentDim + d] = scale * a.outcome(i, (d + 3) % kLatentDim);
  return out;
}

// The end of a refusal test: with an episode pending, `refused()` must be kInvalidArgument;
// then `e` and its `twin` (never given the refused calls, one episode behind) run to the end
// and must have the same archive, so the refusals changed nothing.
template <class Refused>
void expect_refused_while_pending_then_same_as_twin(Explorer& e, Explorer& twin, Refused refused) {
  float theta[kThetaDim];
  ASSERT_EQ(e.propose(theta), Status::kOk);
  EXPECT_EQ(refused(), Status::kInvalidArgument);
  float outcome[kLatentDim];
  test::toy_latent_outcome(theta, outcome);
  ASSERT_EQ(e.observe(outcome), Status::kOk);
  step_latent(twin, 1);
  step_latent(twin, 1000);
  step_latent(e, 1000);
  EXPECT_TRUE(same_archive(twin.archive(), e.archive()));
}

TEST(ExplorerRebase, RewritesOutcomesAndModulesKeepsThetaAndTheRunGoesOnDeterministically) {
  const uint8_t order_a[kLatentDim] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const uint8_t order_b[kLatentDim] = {9, 8, 7, 6, 5, 4, 3, 2, 1, 0};
  auto run = [&](std::unique_ptr<Explorer>& e) {
    ASSERT_EQ(e->init(latent_config(order_a, 2)), Status::kOk);
    step_latent(*e, 200);  // bootstrap + 10 steps: between steps
    ASSERT_EQ(e->episode(), 200);
    std::vector<float> theta_before(200 * kThetaDim);
    for (int i = 0; i < 200; ++i)
      e->archive().theta(i, &theta_before[static_cast<size_t>(i) * kThetaDim]);
    const std::vector<float> outcomes = reencoded(e->archive(), 2.0f);
    const float progress[kMaxModules] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f};
    ASSERT_EQ(e->rebase(latent_config(order_b, 2), outcomes.data(), progress), Status::kOk);
    EXPECT_EQ(e->episode(), 200);
    for (int i = 0; i < 200; ++i) {
      float t[kThetaDim];
      e->archive().theta(i, t);
      ASSERT_EQ(std::memcmp(t, &theta_before[static_cast<size_t>(i) * kThetaDim], sizeof t), 0)
          << i;
      for (int d = 0; d < kLatentDim; ++d)
        ASSERT_EQ(e->archive().outcome(i, d), outcomes[static_cast<size_t>(i) * kLatentDim + d]);
    }
    EXPECT_EQ(e->n_modules(), 5);
    EXPECT_EQ(e->module(), -1);  // goal history emptied: its goals were in the old space
    for (int k = 0; k < 5; ++k) EXPECT_FLOAT_EQ(e->interest(k), progress[k]) << "module " << k;
    step_latent(*e, 1000);
    EXPECT_TRUE(e->done());
  };
  expect_run_repeats_bit_for_bit(run);
}

TEST(ExplorerRebase, RefusedMidStepOrForAnotherRunAndThenChangesNothing) {
  const uint8_t order[kLatentDim] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const float progress[kMaxModules] = {};
  auto twin = std::make_unique<Explorer>();  // never rebased: what the refused one must match
  auto e = std::make_unique<Explorer>();
  ASSERT_EQ(twin->init(latent_config(order, 2)), Status::kOk);
  ASSERT_EQ(e->init(latent_config(order, 2)), Status::kOk);
  step_latent(*twin, 203);  // mid-step
  step_latent(*e, 203);
  std::vector<float> outcomes = reencoded(e->archive(), 1.0f);
  EXPECT_EQ(e->rebase(latent_config(order, 2), outcomes.data(), progress),
            Status::kInvalidArgument);

  step_latent(*twin, 2);  // episode 205: between steps
  step_latent(*e, 2);
  outcomes = reencoded(e->archive(), 1.0f);
  ExplorerConfig other_seed = latent_config(order, 2);
  other_seed.seed = 6;
  EXPECT_EQ(e->rebase(other_seed, outcomes.data(), progress), Status::kInvalidArgument);
  ExplorerConfig other_sigma = latent_config(order, 2);
  other_sigma.sigma *= 2;
  EXPECT_EQ(e->rebase(other_sigma, outcomes.data(), progress), Status::kInvalidArgument);
  EXPECT_EQ(e->rebase(latent_config(order, 2), nullptr, progress), Status::kInvalidArgument);
  std::vector<float> bad = outcomes;
  bad[7] = std::nanf("");
  EXPECT_EQ(e->rebase(latent_config(order, 2), bad.data(), progress), Status::kInvalidArgument);
  expect_refused_while_pending_then_same_as_twin(*e, *twin, [&] {
    return e->rebase(latent_config(order, 2), outcomes.data(), progress);
  });
}

// Explorer::explore_around (curio-online's novelty steps): one step explores around the given
// entry, draws no module or goal, and its exploit re-runs that θ without touching interest.
TEST(ExplorerExploreAround, DirectsOneStepAroundTheSourceAndUpdatesNoInterest) {
  const uint8_t order[kLatentDim] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  auto e = std::make_unique<Explorer>();
  auto twin = std::make_unique<Explorer>();  // the same run without the directed step
  ASSERT_EQ(e->init(latent_config(order, 2)), Status::kOk);
  ASSERT_EQ(twin->init(latent_config(order, 2)), Status::kOk);
  step_latent(*e, 200);
  step_latent(*twin, 200);
  float interest_before[kMaxModules];
  for (int k = 0; k < e->n_modules(); ++k) interest_before[k] = e->interest(k);
  const uint32_t steps = e->counters().steps;
  constexpr int kSource = 17;
  ASSERT_EQ(e->explore_around(kSource), Status::kOk);
  float source_theta[kThetaDim];
  e->archive().theta(kSource, source_theta);
  float theta[kThetaDim], outcome[kLatentDim];
  for (int i = 0; i < kEpisodesPerStep; ++i) {
    const EpisodeKind kind = e->kind();
    ASSERT_EQ(e->propose(theta), Status::kOk);
    EXPECT_EQ(e->module(), -1);
    EXPECT_EQ(e->source_episode(), kSource);
    if (kind == EpisodeKind::kExplore) {
      EXPECT_EQ(e->archive().size(), 200 + i);
      EXPECT_NE(std::memcmp(theta, source_theta, sizeof theta), 0) << "explore adds noise";
    } else {
      EXPECT_EQ(std::memcmp(theta, source_theta, sizeof theta), 0) << "exploit re-runs θ_source";
    }
    test::toy_latent_outcome(theta, outcome);
    ASSERT_EQ(e->observe(outcome), Status::kOk);
    if (kind == EpisodeKind::kExplore) {
      EXPECT_EQ(e->archive().recipe(200 + i).parent, kSource);
    }
  }
  EXPECT_EQ(e->counters().steps, steps + 1);
  for (int k = 0; k < e->n_modules(); ++k) EXPECT_EQ(e->interest(k), interest_before[k]) << k;
  // The module choice and goal streams did not move: the next step draws what the twin's did.
  ASSERT_EQ(e->propose(theta), Status::kOk);
  ASSERT_EQ(twin->propose(theta), Status::kOk);
  EXPECT_EQ(e->module(), twin->module());
  ASSERT_GE(e->module(), 0);
  for (int j = 0; j < e->goal_dim(); ++j) EXPECT_EQ(e->goal()[j], twin->goal()[j]);
}

TEST(ExplorerExploreAround, RefusedOutsideAStepStartOrForAMissingEntryAndThenChangesNothing) {
  const uint8_t order[kLatentDim] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  auto e = std::make_unique<Explorer>();
  auto twin = std::make_unique<Explorer>();
  EXPECT_EQ(e->explore_around(0), Status::kNotInitialised);
  ASSERT_EQ(e->init(latent_config(order, 2)), Status::kOk);
  ASSERT_EQ(twin->init(latent_config(order, 2)), Status::kOk);
  step_latent(*e, 50);  // bootstrap
  step_latent(*twin, 50);
  EXPECT_EQ(e->explore_around(10), Status::kInvalidArgument);
  step_latent(*e, 152);  // mid-step
  step_latent(*twin, 152);
  EXPECT_EQ(e->explore_around(10), Status::kInvalidArgument);
  step_latent(*e, 3);  // episode 205: a step starts
  step_latent(*twin, 3);
  EXPECT_EQ(e->explore_around(-1), Status::kInvalidArgument);
  EXPECT_EQ(e->explore_around(205), Status::kInvalidArgument);  // not archived yet
  expect_refused_while_pending_then_same_as_twin(*e, *twin, [&] { return e->explore_around(10); });

  ExplorerConfig rpe = latent_config(order, 2);
  rpe.algorithm = Algorithm::kRpe;
  ASSERT_EQ(e->init(rpe), Status::kOk);
  step_latent(*e, 105);
  EXPECT_EQ(e->explore_around(10), Status::kInvalidArgument);
}

TEST(ExplorerExploreAround, SameCallsGiveTheSameArchiveBitForBit) {
  const uint8_t order[kLatentDim] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  auto run = [&](std::unique_ptr<Explorer>& e) {
    ASSERT_EQ(e->init(latent_config(order, 2)), Status::kOk);
    float theta[kThetaDim], outcome[kLatentDim];
    while (!e->done()) {
      const int ep = e->episode();
      if (ep >= 100 && (ep - 100) % kEpisodesPerStep == 0 && (ep / 5) % 3 == 0) {
        ASSERT_EQ(e->explore_around(ep - 1 - (ep % 7)), Status::kOk);
      }
      ASSERT_EQ(e->propose(theta), Status::kOk);
      test::toy_latent_outcome(theta, outcome);
      ASSERT_EQ(e->observe(outcome), Status::kOk);
    }
  };
  expect_run_repeats_bit_for_bit(run);
}

}  // namespace
}  // namespace curio
