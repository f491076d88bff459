// One joint-target quantization for every path that moves the arm (so the bus and in-process runs
// agree bit for bit):
//   command a ∈ [−1,1] (float, from the motor primitive)
//     → angle_rad = π·a (double)           the joint's angle relative to its parent link
//     → counts = angle_to_counts(angle_rad)  the RPDO target (1 count = 1 µrad)
//     → counts_to_angle(counts)             what the joint servo is told to reach.
// The controller sends `counts`; the simulated joints step the world with counts_to_angle;
// the in-process run (sim::World::rollout_joint_targets, used by curio-lab) goes through
// the same two functions, so bus and in-process runs see identical joint angles.
#pragma once
#include <cstdint>

#include "firmware/explore/config.hpp"
#include "firmware/protocol/arm_messages.hpp"

namespace curio::app {

inline constexpr double kPi = 3.14159265358979323846;

// Joint range: commands are clipped to [−1, 1], so every joint moves within [−π, π]
// relative to its parent link. In counts: round(π·1e6) = 3141593. Nothing outside this
// range is ever sent (Controller) or applied (simulated joints).
inline constexpr int32_t kJointLimitCounts = 3141593;

// a → counts through angle_to_counts(π·a). kOutOfRange for NaN or |π·a| beyond int32 counts.
protocol::CodecStatus command_to_counts(float command, int32_t* counts);

constexpr bool within_joint_limits(int32_t counts, int32_t limit = kJointLimitCounts) {
  return counts >= -limit && counts <= limit;
}

// The relative joint angles (rad) that commands a ∈ [−1,1]^7 become after the round trip
// through counts. Returns false (angles untouched) if a command is not representable or
// outside the joint limits.
bool quantized_joint_angles(const float commands[kJoints], double angle_rad[kJoints]);

}  // namespace curio::app
