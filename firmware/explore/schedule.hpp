// The step schedule of goal exploration (SPEC §2.2): each step is 4 explore episodes around
// the nearest neighbour of one goal, then 1 exploit episode of that goal.
#pragma once
#include "firmware/explore/config.hpp"

namespace curio {

inline constexpr int kExploreEpisodesPerStep = 4;
inline constexpr int kEpisodesPerStep = kExploreEpisodesPerStep + 1;
// At most one exploit (and so one interest update) per step.
inline constexpr int kGoalHistoryCapacity = kArchiveCapacity / kEpisodesPerStep + 1;

}  // namespace curio
