// The recorded trials' tools (docs/training.md) as training hooks: re-initialisation after
// the warm-up, revival, pruning by reconstruction cost, encoder/decoder freezes, dormant-unit
// recycling and the fixed read-out of active latents; and the trials' weight initialisation.
#pragma once
#include <memory>
#include <vector>

#include "host_tools/vae/recipe.hpp"
#include "host_tools/train/training_hook.hpp"
#include "host_tools/vae/vae_model.hpp"

namespace curio::train {

// The hooks the trial options switch on, in the order their calls must run (recycling before
// the read-out is restored); none for the shipped recipe's defaults.
std::vector<std::unique_ptr<TrainingHook>> make_trial_hooks(const TrialOptions& trial);

// Kaiming init with enc.fc_out × recipe.out_init_scale; with --init torch-default (a trial)
// the layers keep LibTorch's construction init and only enc.fc_out is scaled.
void initialise_weights(Vae& model, const Recipe& recipe);

}  // namespace curio::train
