#include "host_tools/experiment/checkpoints.hpp"

#include <algorithm>

namespace curio::lab {

std::vector<int> spec_checkpoints(int total_episodes) {
  std::vector<int> out;
  for (int i = 0; i < 30; ++i) {
    const int n = i * 10000 / 30;
    if (n <= total_episodes) out.push_back(n);
  }
  return out;
}

std::vector<int> curve_checkpoints(int total_episodes) {
  std::vector<int> out = spec_checkpoints(total_episodes);
  for (int n = 100; n <= total_episodes; n += 100) out.push_back(n);
  out.push_back(total_episodes);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace curio::lab
