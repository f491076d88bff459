// Goals from the archive's sparse regions (GoalKind::kSparseArchive): a departure from SPEC
// §2.3, for goal spaces whose code folds (docs/online.md, "Session 15").
//
// Why: SPEC §2.3 draws learned goals from the VAE prior, which covers the outcomes evenly only
// when the code maps the scene onto N(0, I) without folds, as a β-VAE trained on uniform
// scenes does. A goal space learned from the agent's own images folds (the ball's code is a
// spiral), so prior goals pile onto a few of the reached outcomes and coverage stalls. Here
// the goal is a reached outcome, chosen where the reached outcomes are sparse: of
// `candidates` archive entries drawn uniformly, the one whose module outcome lies farthest
// from any other entry's (largest 1-NN distance; ties: the earlier draw). Only the module's
// own outcome values are used, so any goal space works unchanged.
//
// Cost: candidates linear scans of the module's columns per step, O(candidates · n · d)
// (8 × 10,400 × 2 float ops, a few ms on a Cortex-M7 at 480 MHz); no memory.
// Determinism: exactly `candidates` Prng::below() draws per call, in candidate order.
#pragma once

#include "firmware/explore/archive.hpp"
#include "firmware/explore/goal_module.hpp"
#include "firmware/explore/prng.hpp"

namespace curio {

// Squared distance from entry i's module outcome to the nearest other entry's (every entry but
// i itself), or -1 when i is out of range or the archive has no other entry.
float nearest_other_distance_sq(const Archive& archive, const GoalModule& module, int i);

// Writes the module outcome of the sparsest of `candidates` uniformly drawn entries to
// goal[0 .. module.n_dims); returns its archive index, or -1 (goal untouched, no draw) when
// the archive is empty or candidates < 1.
int sparse_archive_goal(const Archive& archive, const GoalModule& module, int candidates,
                        Prng& prng, float* goal);

}  // namespace curio
