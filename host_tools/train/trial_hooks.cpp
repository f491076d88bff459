#include "host_tools/train/trial_hooks.hpp"

#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace curio::train {
namespace {

// --reinit-after-warmup [--reinit-decoder]: fresh layers around z when the warm-up ends.
class ReinitAfterWarmup final : public TrainingHook {
 public:
  void on_iteration_start(TrainingState& st, int64_t it) override {
    const TrialOptions& t = st.recipe.trial;
    if (it != t.warmup) return;
    Vae& model = st.model;
    if (t.reinit_decoder) {
      model->reinit_decoder(st.recipe.out_init_scale);
      forget_adam_state(st.optimizer, *model->dec);
    } else {
      model->reinit_latent_layers(st.recipe.out_init_scale);
    }
    forget_adam_state(st.optimizer, *model->enc->fc_out);
    forget_adam_state(st.optimizer, *model->dec->fc1);
    fmt::print("it {}: warm-up done; re-initialised enc.fc_out and dec.fc1\n", it);
  }
};

// --revive-at [--revive-fresh-decoder]: one revival of a code stuck on one object.
class Revive final : public TrainingHook {
 public:
  void before_latent_stage(TrainingState& st, int64_t it, const torch::Tensor& x) override {
    const TrialOptions& t = st.recipe.trial;
    if (it != t.revive_at) return;
    std::array<int, 11> n{};
    const LatentMask revived =
        st.model->revive(x, t.recycle_threshold, t.recycle_outgoing_scale, st.recipe.out_init_scale,
                         0.1, t.revive_fresh_decoder, n);
    st.optimizer.state().clear();
    std::string which;
    for (int l = 0; l < kLatents; ++l)
      if (revived[static_cast<size_t>(l)]) {
        which += fmt::format(" z{}", l);
        st.held[static_cast<size_t>(l)] = false;
      }
    fmt::print(
        "it {}: revived: encoder units recycled conv0..3 {} {} {} {} fc1 {} fc2 {}; "
        "decoder {}; fresh latents{}\n",
        it, n[0], n[1], n[2], n[3], n[4], n[5],
        t.revive_fresh_decoder ? std::string("re-initialised")
                               : fmt::format("units recycled fc1 {} fc2 {} deconv0..2 {} {} {}",
                                             n[6], n[7], n[8], n[9], n[10]),
        which);
  }
};

// --prune-by recon: a falling stage holds the latents whose loss costs least reconstruction.
class PruneByReconstruction final : public TrainingHook {
 public:
  bool pruning_importance(TrainingState& st, const torch::Tensor& x,
                          std::array<double, kLatents>& importance) override {
    importance = st.model->reconstruction_cost_of_each_latent(x);
    return true;
  }
};

// --freeze-encoder-from/-to [--freeze-convs-only] [--freeze-decoder-too].
class FeatureFreeze final : public TrainingHook {
 public:
  void after_backward(TrainingState& st, int64_t it) override {
    const TrialOptions& t = st.recipe.trial;
    if (!encoder_frozen_at(t, it)) return;
    st.model->drop_encoder_feature_gradients(t.freeze_convs_only);
    if (t.freeze_decoder_too) st.model->drop_decoder_feature_gradients();
  }
};

// --recycle-every [--recycle-decoder-too]: dormant feature units get fresh weights.
class DormantUnitRecycling final : public TrainingHook {
 public:
  void after_step(TrainingState& st, int64_t it, const torch::Tensor& x) override {
    const TrialOptions& t = st.recipe.trial;
    if ((it + 1) % t.recycle_every != 0) return;
    Vae& model = st.model;
    const auto n =
        model->recycle_dormant_encoder_units(x, t.recycle_threshold, t.recycle_outgoing_scale);
    fmt::print("it {}: recycled dormant encoder units conv0..3 {} {} {} {} fc1 {} fc2 {}\n", it + 1,
               n[0], n[1], n[2], n[3], n[4], n[5]);
    if (!t.recycle_decoder_too) return;
    torch::Tensor z;
    {
      torch::NoGradGuard no_grad;
      z = model->enc->forward(x).first;
    }
    const auto d =
        model->recycle_dormant_decoder_units(z, t.recycle_threshold, t.recycle_outgoing_scale);
    fmt::print("it {}: recycled dormant decoder units fc1 {} fc2 {} deconv0..2 {} {} {}\n", it + 1,
               d[0], d[1], d[2], d[3], d[4]);
  }
};

// --freeze-active-readout: the initial model's active latents keep their enc.fc_out rows.
class FrozenActiveReadout final : public TrainingHook {
 public:
  void on_start(TrainingState& st, int64_t start) override {
    if (st.recipe.init_from.empty() || start > 0)
      throw std::runtime_error(
          "--freeze-active-readout needs --init-from and a fresh run (the "
          "frozen latents are chosen from the initial model)");
    std::vector<int64_t> rows;
    std::string which;
    for (int l = 0; l < kLatents; ++l)
      if (st.kl_ema[static_cast<size_t>(l)] > 0.5) {
        rows.push_back(l);
        rows.push_back(l + kLatents);
        which += fmt::format(" z{}", l);
      }
    torch::NoGradGuard no_grad;
    rows_ = torch::tensor(rows, torch::kInt64);
    weight_ = st.model->enc->fc_out->weight.index_select(0, rows_).clone();
    bias_ = st.model->enc->fc_out->bias.index_select(0, rows_).clone();
    fmt::print("it 0: read-out of the active latents{} held fixed\n", which);
  }
  // After the step and any recycling, so neither the gradient, Adam's momentum nor a
  // recycled unit's fresh outgoing weights move them.
  void after_step(TrainingState& st, int64_t, const torch::Tensor&) override {
    torch::NoGradGuard no_grad;
    st.model->enc->fc_out->weight.index_copy_(0, rows_, weight_);
    st.model->enc->fc_out->bias.index_copy_(0, rows_, bias_);
  }

 private:
  torch::Tensor rows_, weight_, bias_;
};

}  // namespace

std::vector<std::unique_ptr<TrainingHook>> make_trial_hooks(const TrialOptions& t) {
  std::vector<std::unique_ptr<TrainingHook>> hooks;
  if (t.reinit_after_warmup && t.warmup > 0) hooks.push_back(std::make_unique<ReinitAfterWarmup>());
  if (t.revive_at >= 0) hooks.push_back(std::make_unique<Revive>());
  if (t.prune_by == "recon") hooks.push_back(std::make_unique<PruneByReconstruction>());
  if (t.freeze_encoder_from >= 0) hooks.push_back(std::make_unique<FeatureFreeze>());
  if (t.recycle_every > 0) hooks.push_back(std::make_unique<DormantUnitRecycling>());
  if (t.freeze_active_readout) hooks.push_back(std::make_unique<FrozenActiveReadout>());
  return hooks;
}

void initialise_weights(Vae& model, const Recipe& recipe) {
  if (recipe.trial.init == "kaiming")
    model->kaiming_init(recipe.out_init_scale);
  else
    model->scale_encoder_output(recipe.out_init_scale);
}

}  // namespace curio::train
