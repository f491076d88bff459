// The recorded trials' hooks (trial_hooks.hpp): which options switch which hook on, and what
// each hook does to the model and the optimiser at its point of the loop.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "host_tools/train/trial_hooks.hpp"

namespace curio::train {
namespace {

// A small run's state: a Kaiming model with the gradients of one batch x, and its Adam (no
// moments until a test steps it).
struct SmallRun {
  Recipe recipe;
  Vae model;
  torch::optim::Adam optimizer{model->parameters(), torch::optim::AdamOptions(1e-3)};
  LatentMask held{};
  std::array<double, kLatents> kl_ema{};
  TrainingState st{recipe, model, optimizer, held, kl_ema};
  torch::Tensor x;

  explicit SmallRun(const TrialOptions& trial) {
    recipe.trial = trial;
    torch::manual_seed(5);
    model->kaiming_init(1.0);
    x = torch::rand({8, 3, 64, 64});
    step();
  }
  void step() {
    auto [mu, logvar] = model->enc->forward(x);
    const auto loss = torch::binary_cross_entropy_with_logits(model->dec->forward(mu), x) +
                      kl_per_latent(mu, logvar).sum();
    optimizer.zero_grad();
    loss.backward();
  }
  bool has_adam_state(const torch::Tensor& p) {
    return optimizer.state().count(c10::guts::to_string(p.unsafeGetTensorImpl())) > 0;
  }
};

TEST(TrialHooks, TheShippedRecipeRunsWithoutHooksAndEachTrialAddsOne) {
  EXPECT_TRUE(make_trial_hooks(TrialOptions{}).empty());
  TrialOptions warmup_only;
  warmup_only.reinit_after_warmup = true;  // without a warm-up there is nothing to end
  EXPECT_TRUE(make_trial_hooks(warmup_only).empty());
  std::vector<TrialOptions> one_each(6);
  one_each[0].reinit_after_warmup = true, one_each[0].warmup = 10;
  one_each[1].revive_at = 0;
  one_each[2].prune_by = "recon";
  one_each[3].freeze_encoder_from = 0;
  one_each[4].recycle_every = 5;
  one_each[5].freeze_active_readout = true;
  for (const auto& t : one_each) EXPECT_EQ(make_trial_hooks(t).size(), 1u);
}

TEST(TrialHooks, ReinitAfterWarmupFreshensTheLayersAroundZOnceWithFreshAdamState) {
  TrialOptions t;
  t.reinit_after_warmup = true;
  t.warmup = 3;
  SmallRun run(t);
  run.optimizer.step();
  const auto hooks = make_trial_hooks(t);
  const auto before = run.model->enc->fc_out->weight.clone();
  hooks[0]->on_iteration_start(run.st, 2);
  EXPECT_TRUE(torch::equal(before, run.model->enc->fc_out->weight));
  hooks[0]->on_iteration_start(run.st, 3);
  EXPECT_FALSE(torch::equal(before, run.model->enc->fc_out->weight));
  EXPECT_FALSE(run.has_adam_state(run.model->enc->fc_out->weight));
  EXPECT_FALSE(run.has_adam_state(run.model->dec->fc1->weight));
  EXPECT_TRUE(run.has_adam_state(run.model->enc->fc1->weight));  // the features keep theirs
  EXPECT_TRUE(run.has_adam_state(run.model->dec->fc2->weight));
}

TEST(TrialHooks, FeatureFreezeDropsTheFeatureGradientsOnlyInItsWindow) {
  TrialOptions t;
  t.freeze_encoder_from = 10;
  t.freeze_encoder_to = 20;
  t.freeze_decoder_too = true;
  SmallRun run(t);
  const auto hooks = make_trial_hooks(t);
  hooks[0]->after_backward(run.st, 9);
  EXPECT_TRUE(run.model->enc->conv0->weight.grad().defined());
  hooks[0]->after_backward(run.st, 10);
  EXPECT_FALSE(run.model->enc->conv0->weight.grad().defined());
  EXPECT_FALSE(run.model->enc->fc2->weight.grad().defined());
  EXPECT_FALSE(run.model->dec->deconv0->weight.grad().defined());
  EXPECT_TRUE(run.model->enc->fc_out->weight.grad().defined());  // the layers touching z learn
  EXPECT_TRUE(run.model->dec->fc1->weight.grad().defined());
}

TEST(TrialHooks, FrozenActiveReadoutPutsTheActiveRowsBackAfterEachStep) {
  TrialOptions t;
  t.freeze_active_readout = true;
  SmallRun run(t);
  const auto hooks = make_trial_hooks(t);
  EXPECT_THROW(hooks[0]->on_start(run.st, 0), std::runtime_error);  // needs --init-from
  run.recipe.init_from = "initial/checkpoint.pt";
  EXPECT_THROW(hooks[0]->on_start(run.st, 100), std::runtime_error);  // and a fresh run
  run.kl_ema[2] = 3.0;  // z2 is the initial model's one active latent
  hooks[0]->on_start(run.st, 0);
  const auto before = run.model->enc->fc_out->weight.clone();
  run.optimizer.step();
  hooks[0]->after_step(run.st, 0, run.x);
  const auto& after = run.model->enc->fc_out->weight;
  EXPECT_TRUE(torch::equal(before[2], after[2]));                        // μ row
  EXPECT_TRUE(torch::equal(before[2 + kLatents], after[2 + kLatents]));  // log σ² row
  EXPECT_FALSE(torch::equal(before[3], after[3]));                       // the rest trains
}

TEST(TrialHooks, PruneByReconstructionMeasuresWhatEachLatentCarries) {
  TrialOptions t;
  t.prune_by = "recon";
  SmallRun run(t);
  std::array<double, kLatents> importance = run.kl_ema;
  ASSERT_TRUE(make_trial_hooks(t)[0]->pruning_importance(run.st, run.x, importance));
  torch::NoGradGuard no_grad;
  EXPECT_EQ(importance, run.model->reconstruction_cost_of_each_latent(run.x));
}

}  // namespace
}  // namespace curio::train
