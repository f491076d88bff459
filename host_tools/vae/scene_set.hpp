// The training and held-out image sets: the passive-phase data set (SPEC §3: ball and
// distractor independently uniform in [-1,1]²) or an exploration's own scenes (a CSV),
// rendered once into one uint8 tensor (12 KiB an image, so 100k images fit in 1.2 GB) that
// batches are gathered from.
#pragma once
#include <cstdint>
#include <string>

#include <torch/torch.h>

namespace curio::train {

struct SceneSet {
  torch::Tensor images;   // uint8 [N,3,64,64] (NCHW), value = round(255 · pixel)
  torch::Tensor factors;  // float32 [N,4]: ball x, ball y, distractor x, distractor y
};

// Positions drawn in order (ball x, ball y, distractor x, distractor y per image) from
// curio::Prng(seed, stream), so the set depends only on (n, seed, stream), not on `threads`.
// ball_spread < 1 draws the ball in [-ball_spread, ball_spread]² instead (the same PRNG
// draws, scaled): a curriculum that departs from SPEC §3 (docs/training.md, "The β-VAE recipe").
SceneSet render_scene_set(int64_t n, uint64_t seed, uint64_t stream, int threads,
                          double ball_spread = 1.0);

// The scenes of a CSV written by `curio-lab run --save-scenes` (header
// "episode,ball_x,ball_y,distractor_x,distractor_y", one row per episode), rendered with the
// same renderer: the images an exploration's agent saw, in episode order. Throws
// std::runtime_error naming the file and line of the first malformed row.
SceneSet load_scene_set_csv(const std::string& path, int threads);

// Renders given scenes (float32 [N,4]: ball x, ball y, distractor x, distractor y) with the
// same renderer and rounding: the online mode keeps positions, not pixels (host_tools/online).
SceneSet render_scenes(torch::Tensor factors, int threads);

// Rows `index` (int64 [B]) of a uint8 image tensor as float32 in [0,1].
torch::Tensor gather_images(const torch::Tensor& images_u8, const torch::Tensor& index);

// uint8 [B,3,64,64] → float32 in [0,1].
torch::Tensor to_float(const torch::Tensor& images_u8);

}  // namespace curio::train
