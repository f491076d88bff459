#include "host_tools/vae/trial_options.hpp"

namespace curio::train {

bool encoder_frozen_at(const TrialOptions& t, int64_t it) {
  if (t.freeze_encoder_from < 0 || it < t.freeze_encoder_from) return false;
  return t.freeze_encoder_to < 0 || it < t.freeze_encoder_to;
}

void add_to_json(const TrialOptions& t, nlohmann::json& j) {
  j["lr_warmup"] = t.lr_warmup;
  j["lr_decay_from"] = t.lr_decay_from;
  j["lr_final"] = t.lr_final;
  j["warmup"] = t.warmup;
  j["beta_ramp"] = t.beta_ramp;
  j["reinit_after_warmup"] = t.reinit_after_warmup;
  j["reinit_decoder"] = t.reinit_decoder;
  j["prune_by"] = t.prune_by;
  j["init"] = t.init;
  j["vae_window_from"] = t.vae_window_from;
  j["vae_window_to"] = t.vae_window_to;
  j["freeze_encoder_from"] = t.freeze_encoder_from;
  j["freeze_encoder_to"] = t.freeze_encoder_to;
  j["freeze_convs_only"] = t.freeze_convs_only;
  j["freeze_decoder_too"] = t.freeze_decoder_too;
  j["recycle_every"] = t.recycle_every;
  j["recycle_threshold"] = t.recycle_threshold;
  j["recycle_outgoing_scale"] = t.recycle_outgoing_scale;
  j["recycle_decoder_too"] = t.recycle_decoder_too;
  j["revive_at"] = t.revive_at;
  j["revive_fresh_decoder"] = t.revive_fresh_decoder;
  j["freeze_active_readout"] = t.freeze_active_readout;
}

TrialOptions trial_options_from_json(const nlohmann::json& j) {
  const TrialOptions d;  // the defaults stand for keys that older recipe.json files lack
  TrialOptions t;
  t.lr_warmup = j.value("lr_warmup", d.lr_warmup);
  t.lr_decay_from = j.value("lr_decay_from", d.lr_decay_from);
  t.lr_final = j.value("lr_final", d.lr_final);
  t.warmup = j.value("warmup", d.warmup);
  t.beta_ramp = j.value("beta_ramp", d.beta_ramp);
  t.reinit_after_warmup = j.value("reinit_after_warmup", d.reinit_after_warmup);
  t.reinit_decoder = j.value("reinit_decoder", d.reinit_decoder);
  t.prune_by = j.value("prune_by", d.prune_by);
  t.init = j.value("init", d.init);
  t.vae_window_from = j.value("vae_window_from", d.vae_window_from);
  t.vae_window_to = j.value("vae_window_to", d.vae_window_to);
  t.freeze_encoder_from = j.value("freeze_encoder_from", d.freeze_encoder_from);
  t.freeze_encoder_to = j.value("freeze_encoder_to", d.freeze_encoder_to);
  t.freeze_convs_only = j.value("freeze_convs_only", d.freeze_convs_only);
  t.freeze_decoder_too = j.value("freeze_decoder_too", d.freeze_decoder_too);
  t.recycle_every = j.value("recycle_every", d.recycle_every);
  t.recycle_threshold = j.value("recycle_threshold", d.recycle_threshold);
  t.recycle_outgoing_scale = j.value("recycle_outgoing_scale", d.recycle_outgoing_scale);
  t.recycle_decoder_too = j.value("recycle_decoder_too", d.recycle_decoder_too);
  t.revive_at = j.value("revive_at", d.revive_at);
  t.revive_fresh_decoder = j.value("revive_fresh_decoder", d.revive_fresh_decoder);
  t.freeze_active_readout = j.value("freeze_active_readout", d.freeze_active_readout);
  return t;
}

}  // namespace curio::train
