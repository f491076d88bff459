// A stand-in for the simulated arm on the bus (7 CiA 402 joints in cyclic synchronous position
// mode and the camera node), and a controller-side loop that times whole episodes against
// it: 50 control periods (7 RPDO1 + SYNC → 7 TPDO1) and one 12,288-byte camera frame over
// ISO-TP. It measures the bus, not physics: the joints report their target, the camera sends a
// fixed test pattern.
#pragma once
#include <cstdint>

#include "hal/can_bus.hpp"

namespace curio::hal::tools {

// Serves until `idle_timeout_us` passes without a frame. Returns 0.
int run_mock_arm(CanBus& bus, uint64_t idle_timeout_us);

struct EpisodeBenchResult {
  int episodes = 0;
  double cycle_mean_us = 0;    // one control period: RPDOs + SYNC out, 7 TPDOs in
  double cycle_worst_us = 0;   // slowest episode's mean period
  double image_median_us = 0;  // capture request to complete image
  double episodes_per_s = 0;
  uint64_t frames_per_episode = 0;  // both directions
  double reads_per_cycle = 0;       // receive calls until all 7 TPDOs were in
  bool ok = false;
};

EpisodeBenchResult run_episode_bench(CanBus& bus, int episodes);

}  // namespace curio::hal::tools
