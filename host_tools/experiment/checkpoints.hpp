// Episode counts at which the exploration ratio is recorded: SPEC §4's
// N_i = ⌊i·10000/30⌋ (i = 0..29) and every 100 episodes for smooth curves, up to the total.
#pragma once
#include <vector>

namespace curio::lab {

std::vector<int> spec_checkpoints(int total_episodes);
std::vector<int> curve_checkpoints(int total_episodes);  // SPEC ones ∪ multiples of 100 ∪ total

}  // namespace curio::lab
