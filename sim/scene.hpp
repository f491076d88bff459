// Fixed facts of the Arm-2-Balls scene (SPEC §1.1): arm geometry and the state
// every episode starts from. Shared by both physics and the tests.
#pragma once
#include "firmware/explore/config.hpp"
#include "sim/world.hpp"

namespace curio::sim {

inline constexpr double kPi = 3.14159265358979323846;

// Link lengths from the base outwards; they sum to 1 (reachable set: the unit disc).
inline constexpr double kLinkLengths[kJoints] = {0.3, 0.2, 0.2, 0.1, 0.1, 0.05, 0.05};

inline constexpr Vec2 kHandStart{1.0, 0.0};
inline constexpr Vec2 kBallStart{0.6, 0.6};
inline constexpr Vec2 kDistractorStart{0.7, -0.45};

// The distractor walk is clipped to this box per coordinate.
inline constexpr double kDistractorBound = 0.95;

// Scene radii in world units (SPEC §1.4), used by the renderer.
inline constexpr double kBallRadius = 0.17;
inline constexpr double kDistractorRadius = 0.15;

}  // namespace curio::sim
