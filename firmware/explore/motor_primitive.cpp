#include "firmware/explore/motor_primitive.hpp"

#include <cmath>

namespace curio {

MotorPrimitive::MotorPrimitive() {
  for (int t = 0; t < kStepsPerEpisode; ++t) {
    for (int k = 0; k < kBasisPerJoint; ++k) {
      const float d = static_cast<float>(t) - kCentres[k];
      basis_[t][k] = std::fabs(d) <= kTruncation
                         ? static_cast<float>(std::exp(-static_cast<double>(d) * d /
                                                       (2.0 * kWidth * kWidth)))
                         : 0.0f;
    }
  }
}

void MotorPrimitive::commands(const float theta[kThetaDim], int t, float out[kJoints]) const {
  for (int j = 0; j < kJoints; ++j) {
    float a = 0.0f;
    for (int k = 0; k < kBasisPerJoint; ++k) a += basis_[t][k] * theta[kBasisPerJoint * j + k];
    out[j] = a > 1.0f ? 1.0f : (a < -1.0f ? -1.0f : a);
  }
}

}  // namespace curio
