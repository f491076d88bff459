// Steps 2–3 of SPEC §1.1, shared by both physics: the ball is grasped when the hand
// is strictly closer than the grasp radius; from then on it is in the hand and is
// never released within the episode.
#pragma once
#include <cmath>

#include "sim/world.hpp"

namespace curio::sim {

inline void apply_grasp_rule(double grasp_radius, SceneState* scene) {
  if (!scene->grasped) {
    const double dx = scene->hand.x - scene->ball.x;
    const double dy = scene->hand.y - scene->ball.y;
    // ‖hand − ball‖ written as the reference computes it (sqrt of the dot product).
    scene->grasped = std::sqrt(dx * dx + dy * dy) < grasp_radius;
  }
  if (scene->grasped) scene->ball = scene->hand;
}

}  // namespace curio::sim
