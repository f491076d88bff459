// Bit-for-bit equality of scene states, for determinism tests.
#pragma once
#include "sim/world.hpp"

namespace curio::sim {

inline bool identical(const SceneState& a, const SceneState& b) {
  return a.grasped == b.grasped && a.hand.x == b.hand.x && a.hand.y == b.hand.y &&
         a.ball.x == b.ball.x && a.ball.y == b.ball.y && a.distractor.x == b.distractor.x &&
         a.distractor.y == b.distractor.y;
}

}  // namespace curio::sim
