#include "firmware/explore/explorer_config.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>

#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"

namespace curio {
namespace {

ExplorerConfig mge_efr() {
  ExplorerConfig c;
  set_efr_modules(c, Algorithm::kMge);
  return c;
}

TEST(ExplorerConfig, DefaultsAreTheSpecs) {
  const ExplorerConfig c;
  EXPECT_FLOAT_EQ(c.sigma, 0.05f);
  EXPECT_FLOAT_EQ(c.competence_cap, 2.0f);
  EXPECT_FLOAT_EQ(c.window, 1000.0f);
  EXPECT_FLOAT_EQ(c.epsilon, 0.1f);
  EXPECT_FLOAT_EQ(c.goal_bound, 2.5f);
  EXPECT_FLOAT_EQ(c.goal_scale, 1.0f);
  EXPECT_EQ(c.n_bootstrap, 100);
  EXPECT_EQ(c.n_episodes, 10000);
  EXPECT_EQ(c.tie_rule, TieRule::kLatest);
  EXPECT_EQ(validate(mge_efr()), Status::kOk);
}

TEST(ExplorerConfig, RejectsEachOutOfRangeField) {
  const std::function<void(ExplorerConfig&)> breakers[] = {
      [](ExplorerConfig& c) { c.outcome_dim = 0; },
      [](ExplorerConfig& c) { c.outcome_dim = kMaxOutcomeDim + 1; },
      [](ExplorerConfig& c) { c.n_modules = 0; },
      [](ExplorerConfig& c) { c.n_modules = kMaxModules + 1; },
      [](ExplorerConfig& c) { c.algorithm = Algorithm::kRge; },  // 2 modules
      [](ExplorerConfig& c) { c.algorithm = static_cast<Algorithm>(7); },
      [](ExplorerConfig& c) { c.modules[1].n_dims = 0; },
      [](ExplorerConfig& c) { c.modules[1].n_dims = 5; },   // > outcome_dim
      [](ExplorerConfig& c) { c.modules[1].dims[1] = 4; },  // dim ≥ outcome_dim
      [](ExplorerConfig& c) { c.modules[1].dims[1] = 2; },  // repeated dim
      [](ExplorerConfig& c) { c.goal_kind = static_cast<GoalKind>(9); },
      [](ExplorerConfig& c) { c.goal_bound = 0.0f; },
      [](ExplorerConfig& c) { c.goal_scale = 0.0f; },
      [](ExplorerConfig& c) { c.goal_scale = INFINITY; },
      [](ExplorerConfig& c) { c.sigma = -0.1f; },
      [](ExplorerConfig& c) { c.sigma = NAN; },
      [](ExplorerConfig& c) { c.competence_cap = 0.0f; },
      [](ExplorerConfig& c) { c.competence_measure = static_cast<CompetenceMeasure>(7); },
      [](ExplorerConfig& c) { c.window = 0.5f; },
      [](ExplorerConfig& c) { c.epsilon = 1.5f; },
      [](ExplorerConfig& c) { c.epsilon = -0.01f; },
      [](ExplorerConfig& c) { c.n_bootstrap = -1; },
      [](ExplorerConfig& c) { c.n_episodes = -5; },
      [](ExplorerConfig& c) { c.n_episodes = 10001; },  // not whole steps of 5
      [](ExplorerConfig& c) { c.tie_rule = static_cast<TieRule>(3); },
  };
  int i = 0;
  for (const auto& breaker : breakers) {
    ExplorerConfig c = mge_efr();
    breaker(c);
    EXPECT_EQ(validate(c), Status::kInvalidConfig) << "breaker " << i;
    ++i;
  }
}

TEST(ExplorerConfig, CapacityTooSmall) {
  ExplorerConfig c = mge_efr();
  c.n_bootstrap = kArchiveCapacity - c.n_episodes;
  EXPECT_EQ(validate(c), Status::kOk);
  c.n_bootstrap += 1;
  EXPECT_EQ(validate(c), Status::kCapacityTooSmall);
  c.algorithm = Algorithm::kRpe;
  EXPECT_EQ(validate(c), Status::kCapacityTooSmall);
}

TEST(ExplorerConfig, RpeIgnoresGoalFields) {
  ExplorerConfig c;
  set_efr_modules(c, Algorithm::kRpe);
  c.sigma = -1.0f;
  c.n_episodes = 7;
  EXPECT_EQ(validate(c), Status::kOk);
}

TEST(ExplorerConfig, InitRefusesInvalidConfigAndStaysUninitialised) {
  auto e = std::make_unique<Explorer>();
  ExplorerConfig c = mge_efr();
  c.epsilon = 2.0f;
  EXPECT_EQ(e->init(c), Status::kInvalidConfig);
  EXPECT_FALSE(e->initialised());
  float theta[kThetaDim];
  EXPECT_EQ(e->propose(theta), Status::kNotInitialised);
  const float outcome[4] = {};
  EXPECT_EQ(e->observe(outcome), Status::kNotInitialised);
  c = mge_efr();
  c.n_episodes = (kArchiveCapacity / 5 + 1) * 5;
  EXPECT_EQ(e->init(c), Status::kCapacityTooSmall);
  EXPECT_FALSE(e->initialised());
}

TEST(ModuleLayouts, EngineeredFeatures) {
  ExplorerConfig c;
  ASSERT_EQ(set_efr_modules(c, Algorithm::kRge), Status::kOk);
  EXPECT_EQ(c.outcome_dim, 4);
  ASSERT_EQ(c.n_modules, 1);
  EXPECT_EQ(c.modules[0].n_dims, 4);
  for (int j = 0; j < 4; ++j) EXPECT_EQ(c.modules[0].dims[j], j);
  EXPECT_EQ(validate(c), Status::kOk);

  ASSERT_EQ(set_efr_modules(c, Algorithm::kMge), Status::kOk);
  ASSERT_EQ(c.n_modules, 2);
  EXPECT_EQ(c.modules[0].dims[0], kEfrDistractorX);
  EXPECT_EQ(c.modules[0].dims[1], kEfrDistractorY);
  EXPECT_EQ(c.modules[1].dims[0], kEfrBallX);
  EXPECT_EQ(c.modules[1].dims[1], kEfrBallY);
  EXPECT_EQ(c.goal_kind, GoalKind::kUniformBox);
  EXPECT_EQ(validate(c), Status::kOk);
}

TEST(ModuleLayouts, LatentGroupsFollowTheKlOrder) {
  const uint8_t kl_order[kLatentDim] = {7, 2, 9, 0, 1, 3, 4, 5, 6, 8};
  ExplorerConfig c;
  ASSERT_EQ(set_latent_modules(c, kl_order, 2), Status::kOk);
  EXPECT_EQ(c.algorithm, Algorithm::kMge);
  EXPECT_EQ(c.outcome_dim, 10);
  EXPECT_EQ(c.goal_kind, GoalKind::kClippedNormal);
  ASSERT_EQ(c.n_modules, 5);
  EXPECT_EQ(c.modules[0].dims[0], 7);
  EXPECT_EQ(c.modules[0].dims[1], 2);
  EXPECT_EQ(c.modules[1].dims[0], 9);
  EXPECT_EQ(c.modules[4].dims[1], 8);
  EXPECT_EQ(validate(c), Status::kOk);

  ASSERT_EQ(set_latent_modules(c, kl_order, 1), Status::kOk);
  ASSERT_EQ(c.n_modules, 10);
  EXPECT_EQ(c.modules[9].n_dims, 1);
  EXPECT_EQ(c.modules[9].dims[0], 8);
  EXPECT_EQ(validate(c), Status::kOk);

  ASSERT_EQ(set_latent_modules(c, kl_order, 10), Status::kOk);
  EXPECT_EQ(c.algorithm, Algorithm::kRge);
  ASSERT_EQ(c.n_modules, 1);
  EXPECT_EQ(c.modules[0].n_dims, 10);
  EXPECT_EQ(validate(c), Status::kOk);

  EXPECT_EQ(set_latent_modules(c, kl_order, 3), Status::kInvalidArgument);
  const uint8_t not_perm[kLatentDim] = {0, 0, 1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_EQ(set_latent_modules(c, not_perm, 2), Status::kInvalidArgument);
}

}  // namespace
}  // namespace curio
