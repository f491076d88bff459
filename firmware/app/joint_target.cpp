#include "firmware/app/joint_target.hpp"

namespace curio::app {

protocol::CodecStatus command_to_counts(float command, int32_t* counts) {
  return protocol::angle_to_counts(kPi * static_cast<double>(command), counts);
}

bool quantized_joint_angles(const float commands[kJoints], double angle_rad[kJoints]) {
  double out[kJoints];
  for (int j = 0; j < kJoints; ++j) {
    int32_t counts = 0;
    if (command_to_counts(commands[j], &counts) != protocol::CodecStatus::kOk) return false;
    if (!within_joint_limits(counts)) return false;
    out[j] = protocol::counts_to_angle(counts);
  }
  for (int j = 0; j < kJoints; ++j) angle_rad[j] = out[j];
  return true;
}

}  // namespace curio::app
