// ε-proportional module choice (SPEC §2.5): p(i) = (1 − ε)·I_i / ΣI + ε / N,
// uniform when ΣI = 0. One uniform01 draw per choice (inverse CDF, modules in index order).
#pragma once
#include "firmware/explore/prng.hpp"

namespace curio {

// Module index in [0, n). Interests must be ≥ 0; n ≥ 1; 0 ≤ ε ≤ 1.
int choose_module(const float* interest, int n, float epsilon, Prng& prng);

// p(i) of the rule above, for tests and logs.
double module_probability(const float* interest, int n, float epsilon, int i);

}  // namespace curio
