// The RBF motor primitive of SPEC §1.2: θ ∈ [-1,1]^49 (joint-major, P[j][k] = θ[7j+k])
// → per-step joint commands a_j(t) = clip(Σ_k φ_k(t)·P[j][k], −1, 1), t = 0..49.
#pragma once
#include "firmware/explore/config.hpp"

namespace curio {

class MotorPrimitive {
 public:
  static constexpr float kCentres[kBasisPerJoint] = {8, 15, 22, 29, 36, 43, 50};
  static constexpr float kWidth = 10.0f;     // σ of each Gaussian basis
  static constexpr float kTruncation = 40.0f;  // φ_k(t) = 0 beyond |t − c_k| > 40

  MotorPrimitive();

  // φ_k(t), precomputed at construction.
  float basis(int t, int k) const { return basis_[t][k]; }

  // Commands of all joints at step t, each in [-1, 1].
  void commands(const float theta[kThetaDim], int t, float out[kJoints]) const;

 private:
  float basis_[kStepsPerEpisode][kBasisPerJoint];
};

}  // namespace curio
