// The RBF basis the world is driven by (SPEC §1.2), as the simulator relies on it.
#include <gtest/gtest.h>

#include "firmware/explore/motor_primitive.hpp"

namespace curio {
namespace {

TEST(MotorPrimitiveBasis, ValuesAtStepZeroMatchSpec) {
  const MotorPrimitive primitive;
  const double expected[kBasisPerJoint] = {0.7261, 0.3247, 0.0889, 0.0149, 0.0015, 0.0, 0.0};
  for (int k = 0; k < kBasisPerJoint; ++k) {
    EXPECT_NEAR(primitive.basis(0, k), expected[k], 5e-5) << "k=" << k;
  }
}

TEST(MotorPrimitiveBasis, TruncatedBeyondFortyStepsFromCentre) {
  const MotorPrimitive primitive;
  // Centre 50: |t − 50| = 41 at t = 9 is cut, 40 at t = 10 is kept (exp(−8)).
  EXPECT_EQ(primitive.basis(9, 6), 0.0f);
  EXPECT_NEAR(primitive.basis(10, 6), 3.3546e-4, 1e-7);
  // Centre 43 at t = 2 (distance 41) is cut; so is centre 8 at the last step t = 49.
  EXPECT_EQ(primitive.basis(2, 5), 0.0f);
  EXPECT_EQ(primitive.basis(49, 0), 0.0f);
  EXPECT_GT(primitive.basis(48, 0), 0.0f);
}

TEST(MotorPrimitiveBasis, CommandsAreClippedToUnitRange) {
  const MotorPrimitive primitive;
  float theta[kThetaDim];
  for (float& v : theta) v = 1.0f;
  float a[kJoints];
  for (int t = 0; t < kStepsPerEpisode; ++t) {
    primitive.commands(theta, t, a);
    for (float v : a) EXPECT_EQ(v, 1.0f);  // Σφ > 1 at every step
  }
}

}  // namespace
}  // namespace curio
