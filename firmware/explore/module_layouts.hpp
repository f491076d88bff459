// The standard module layouts of SPEC §2.1 and §2.4, filled into an ExplorerConfig.
#pragma once
#include <cstdint>

#include "firmware/explore/explorer_config.hpp"

namespace curio {

// Engineered-feature outcome: [distractor x, distractor y, ball x, ball y] at t = 49.
inline constexpr int kEfrOutcomeDim = 4;
inline constexpr uint8_t kEfrDistractorX = 0;
inline constexpr uint8_t kEfrDistractorY = 1;
inline constexpr uint8_t kEfrBallX = 2;
inline constexpr uint8_t kEfrBallY = 3;
// Learned outcome: the encoder mean μ.
inline constexpr int kLatentDim = 10;
static_assert(kLatentDim <= kMaxOutcomeDim && kEfrOutcomeDim <= kMaxOutcomeDim);

// Sets algorithm, outcome_dim = 4, goal_kind = kUniformBox and the modules:
// RGE: one module {0,1,2,3}; MGE: module 0 = distractor {0,1}, module 1 = ball {2,3};
// RPE: no modules. Other fields untouched.
Status set_efr_modules(ExplorerConfig& config, Algorithm algorithm);

// Learned latents: `kl_order` lists the 10 latent indices by decreasing KL (a permutation of
// 0..9); modules are its consecutive groups of `group_size` (2 → 5 pairs, 1 → 10 singles,
// 10 → 1 group; any divisor of 10). Sets outcome_dim = 10, goal_kind = kClippedNormal and
// algorithm = RGE for one group, MGE otherwise. kInvalidArgument if kl_order is not a
// permutation or group_size does not divide 10 (config untouched).
Status set_latent_modules(ExplorerConfig& config, const uint8_t kl_order[kLatentDim],
                          int group_size);

}  // namespace curio
