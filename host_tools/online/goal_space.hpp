// The learned goal space of an online run at one moment: the float encoder's μ of the agent's
// final images, the latents' KL on those images, and the goal modules made from the KL order
// (SPEC §2.4: consecutive groups of the latents by decreasing KL, 2-D as MGE-βVAE).
//
// Encoding is the LibTorch float encoder (the model being trained), not the int8 path: the
// model changes every retrain, and quantizing each one would add calibration noise that
// differs between retrains. Images are rendered from stored final scene states with
// sim::render_scene and rounded to uint8 exactly as the trainer's images are.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <torch/torch.h>

#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "host_tools/vae/scene_set.hpp"
#include "host_tools/vae/vae_model.hpp"

namespace curio::online {

// One episode's final scene: ball x, y, distractor x, y (what the camera shows; the arm is
// not drawn by sim::render_scene). 16 bytes an episode instead of a 12 KiB image.
using Scene = std::array<float, 4>;

// Evaluation only (reads the true ball position): the ball ended away from its rest spot
// sim::kBallStart (more than 1e-3 in x or y).
bool ball_moved(const Scene& scene);

// The scenes rendered (train::render_scenes), with their positions as the factors (which
// only evaluation reads).
train::SceneSet scene_set_of(const std::vector<Scene>& scenes, int threads);
// uint8 [N,3,64,64] images of the scenes.
torch::Tensor render_images(const std::vector<Scene>& scenes, int threads);

struct EncodedScenes {
  std::vector<float> mu;              // N × 10, row-major (the explorer's outcomes)
  std::array<double, 10> kl{};        // mean KL per latent over the images (nats)
  std::array<uint8_t, 10> kl_order{}; // latent indices by decreasing KL (ties: lower index)
  std::array<double, 10> mu_mean{};   // mean and (population) sd of each latent's μ over the images
  std::array<double, 10> mu_sd{};
  std::vector<double> recon;          // BCE per image decoding μ (nats); only when asked
};

// The latents ordered group by group: the groups of group_size consecutive latents (z0..,
// then the next group_size, ...) by decreasing summed KL, each group's latents by decreasing
// KL (ties: lower index). With progressive latents a group is the latents opened together,
// so the modules (consecutive runs of this order) are the opened groups.
std::array<uint8_t, 10> group_order(const std::array<double, 10>& kl, int group_size);

// μ and KL of every image (batches, no gradients).
EncodedScenes encode_images(train::Vae& model, const torch::Tensor& images_u8, bool with_recon = false);

// μ of one scene (the outcome of the episode just run); with `recon_bce`, also the BCE of
// its image decoding μ (nats, as EncodedScenes::recon).
void encode_scene(train::Vae& model, const Scene& scene, float out[kLatentDim], double* recon_bce = nullptr);

// `base` with the modules of the KL order (set_latent_modules). Throws on a bad order.
ExplorerConfig goal_space_config(const ExplorerConfig& base, const std::array<uint8_t, 10>& order,
                                 int group_size);

// cp of each module of `next` carried over from `explorer`'s current modules, by latent:
// each latent keeps the cp of the old module that held it, and a new module starts at the
// mean of its latents' cp. Warm-started latents mostly keep their meaning, so the interest
// the agent built in (say) the ball's latents survives a retrain that reorders the modules.
std::vector<float> carried_progress(const Explorer& explorer, const ExplorerConfig& next);

// The latents of each module of `config`, as ints.
std::vector<std::vector<int>> module_latents(const ExplorerConfig& config);

}  // namespace curio::online
