// Forward kinematics of the reference model (SPEC §1.1): absolute joint angles are
// the cumulative sum of the commands times π; the hand is the end of the chain.
#pragma once
#include "firmware/explore/config.hpp"
#include "sim/world.hpp"

namespace curio::sim {

// Hand position for joint commands a ∈ [−1,1]^7 (double precision throughout).
Vec2 forward_kinematics(const float commands[kJoints]);

// Hand position for joint angles relative to their parent links (rad): absolute
// angle_j = Σ_{i≤j} angle_i.
Vec2 forward_kinematics_angles(const double angle_rad[kJoints]);

}  // namespace curio::sim
