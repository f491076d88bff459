// A short MGE-EFR exploration on an arithmetic-only toy world, reduced to one checksum over
// the archive (θ and outcomes, bit patterns) and the final interests. Shared by the host test
// and the Cortex-M7 QEMU test: both must print kSmokeChecksum, which shows the core computes
// the same run bit for bit on x86 and ARM (integer PRNG; IEEE float +,−,×,/ without FMA).
// Firmware-clean: no heap, no libm in the world, no standard containers.
#pragma once
#include <cstdint>

#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/explore/fnv1a.hpp"

namespace curio::test {

// Checksum of run_smoke(seed = kSmokeSeed), computed on the host; update it (and say why in
// the commit) whenever the algorithm legitimately changes the sequence of θ.
inline constexpr uint32_t kSmokeChecksum = 0xbae403d0u;
inline constexpr uint64_t kSmokeSeed = 2018;
inline constexpr int kSmokeBootstrap = 50;
inline constexpr int kSmokeEpisodes = 500;
// The full-size run (SPEC §2.2: 100 bootstrap + 10,000 episodes) needs the default capacity.
inline constexpr uint32_t kFullChecksum = 0x91bd4fb9u;
inline constexpr int kFullBootstrap = 100;
inline constexpr int kFullEpisodes = 10000;

// [distractor x, y, ball x, y] from polynomials of θ; the "ball" moves only on a "grasp".
inline void poly_outcome(const float* theta, float* out) {
  const float a = theta[4], b = theta[5];
  out[0] = 0.9f * a * (1.0f - 0.3f * a * a);
  out[1] = 0.8f * b - 0.1f * a * b;
  if (theta[0] + theta[1] > 1.2f) {
    out[2] = 0.95f * theta[2] * (1.0f - 0.1f * theta[3] * theta[3]);
    out[3] = 0.95f * theta[3];
  } else {
    out[2] = 0.6f;
    out[3] = 0.6f;
  }
}

struct SmokeResult {
  Status status = Status::kOk;
  int episodes = 0;
  uint32_t nn_queries = 0;
  uint32_t checksum = 0;
};

inline SmokeResult run_smoke(Explorer& explorer, int n_bootstrap = kSmokeBootstrap,
                             int n_episodes = kSmokeEpisodes, uint64_t seed = kSmokeSeed) {
  SmokeResult r;
  ExplorerConfig config;
  set_efr_modules(config, Algorithm::kMge);
  config.n_bootstrap = n_bootstrap;
  config.n_episodes = n_episodes;
  config.seed = seed;
  r.status = explorer.init(config);
  float theta[kThetaDim];
  float outcome[kEfrOutcomeDim];
  while (r.status == Status::kOk && !explorer.done()) {
    r.status = explorer.propose(theta);
    if (r.status != Status::kOk) break;
    poly_outcome(theta, outcome);
    r.status = explorer.observe(outcome);
    ++r.episodes;
  }
  Fnv1a f;
  f.add_archive(explorer.archive());
  for (int k = 0; k < explorer.n_modules(); ++k) f.add_float(explorer.interest(k));
  r.nn_queries = explorer.counters().nn_queries;
  r.checksum = f.h;
  return r;
}

}  // namespace curio::test
