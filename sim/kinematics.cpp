#include "sim/kinematics.hpp"

#include <cmath>

#include "sim/scene.hpp"

namespace curio::sim {

Vec2 forward_kinematics(const float commands[kJoints]) {
  Vec2 hand;
  double command_sum = 0.0;
  for (int j = 0; j < kJoints; ++j) {
    command_sum += static_cast<double>(commands[j]);
    const double angle_rad = kPi * command_sum;
    hand.x += kLinkLengths[j] * std::cos(angle_rad);
    hand.y += kLinkLengths[j] * std::sin(angle_rad);
  }
  return hand;
}

Vec2 forward_kinematics_angles(const double angle_rad[kJoints]) {
  Vec2 hand;
  double absolute_rad = 0.0;
  for (int j = 0; j < kJoints; ++j) {
    absolute_rad += angle_rad[j];
    hand.x += kLinkLengths[j] * std::cos(absolute_rad);
    hand.y += kLinkLengths[j] * std::sin(absolute_rad);
  }
  return hand;
}

}  // namespace curio::sim
