// Compile-time sizes of the exploration core (SPEC §1.2, §2). Everything the
// firmware stores is sized from these constants; nothing is allocated at run time.
#pragma once
#include <cstdint>

namespace curio {

inline constexpr int kJoints = 7;              // revolute joints of the arm
inline constexpr int kBasisPerJoint = 7;       // RBFs per joint
inline constexpr int kThetaDim = kJoints * kBasisPerJoint;  // 49 motor parameters
inline constexpr int kStepsPerEpisode = 50;    // control periods per episode
inline constexpr int kMaxOutcomeDim = 10;      // 4 engineered features or 10 latents
inline constexpr int kMaxModules = 10;         // 10 single-latent modules at most

#ifndef CURIO_ARCHIVE_CAPACITY
#define CURIO_ARCHIVE_CAPACITY 10400           // 400 bootstrap + 10,000 episodes, exactly
#endif
inline constexpr int kArchiveCapacity = CURIO_ARCHIVE_CAPACITY;

// The archive keeps how each θ was made and regenerates it (archive.hpp); a θ that is
// kThetaPoolDepth noise vectors deep and gets explored around is kept in a pool of
// kThetaPoolCapacity θ, which bounds one regeneration to kThetaPoolDepth noise vectors.
#ifndef CURIO_THETA_POOL_DEPTH
#define CURIO_THETA_POOL_DEPTH 16
#endif
// One pool θ per 40 episodes: MGE-EFR pooled at most 97 θ in a 10,100-episode run over 100
// seeds (tests/bench/archive_depth.cpp, docs/deploy.md).
#ifndef CURIO_THETA_POOL_CAPACITY
#define CURIO_THETA_POOL_CAPACITY ((CURIO_ARCHIVE_CAPACITY + 39) / 40)
#endif
inline constexpr int kThetaPoolDepth = CURIO_THETA_POOL_DEPTH;
inline constexpr int kThetaPoolCapacity = CURIO_THETA_POOL_CAPACITY;

static_assert(kThetaDim == 49, "SPEC §1.2: θ has 7 joints × 7 basis functions");
static_assert(kArchiveCapacity > 0, "archive needs room");
static_assert(kThetaPoolDepth >= 1 && kThetaPoolCapacity >= 0 &&
                  kThetaPoolCapacity <= kArchiveCapacity,
              "the θ pool holds at most one θ per archived episode");

}  // namespace curio
