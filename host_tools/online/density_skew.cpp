#include "host_tools/online/density_skew.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace curio::online {
namespace {

// r(i): distance from point i to its k-th nearest other point (d-dimensional points).
std::vector<double> kth_neighbour_distance(const std::vector<float>& codes, int stride, int n,
                                           const std::vector<int>& dims, int k) {
  std::vector<double> r(static_cast<size_t>(n));
  std::vector<float> pts(static_cast<size_t>(n) * dims.size());
  for (int i = 0; i < n; ++i)
    for (size_t j = 0; j < dims.size(); ++j)
      pts[static_cast<size_t>(i) * dims.size() + j] = codes[static_cast<size_t>(i) * stride + dims[j]];
  std::vector<float> d2(static_cast<size_t>(n));
  const size_t d = dims.size();
  for (int i = 0; i < n; ++i) {
    const float* a = &pts[static_cast<size_t>(i) * d];
    for (int e = 0; e < n; ++e) {
      const float* b = &pts[static_cast<size_t>(e) * d];
      float s = 0.0f;
      for (size_t j = 0; j < d; ++j) {
        const float x = a[j] - b[j];
        s += x * x;
      }
      d2[static_cast<size_t>(e)] = s;
    }
    d2[static_cast<size_t>(i)] = INFINITY;  // not its own neighbour
    std::nth_element(d2.begin(), d2.begin() + (k - 1), d2.end());
    r[static_cast<size_t>(i)] = std::sqrt(static_cast<double>(d2[static_cast<size_t>(k - 1)]));
  }
  return r;
}

}  // namespace

std::vector<double> density_skew_weights(const std::vector<float>& codes, int stride, int n,
                                         const std::vector<std::vector<int>>& modules, int k,
                                         double alpha, double cap) {
  if (n <= 0) return {};
  std::vector<double> logw(static_cast<size_t>(n), 0.0);
  if (n > k && k >= 1) {
    for (const auto& dims : modules) {
      const std::vector<double> r = kth_neighbour_distance(codes, stride, n, dims, k);
      std::vector<double> sorted = r;
      std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
      const double median = sorted[static_cast<size_t>(n / 2)];
      const double spread = *std::max_element(r.begin(), r.end());
      if (!(spread > 0.0)) continue;  // every code equal: no density to skew by
      // Duplicates (r = 0) would get zero weight or an infinite one: floor them.
      const double floor_r = std::max(1e-3 * median, 1e-12);
      for (int i = 0; i < n; ++i)
        logw[static_cast<size_t>(i)] += -alpha * static_cast<double>(dims.size()) *
                                        std::log(std::max(r[static_cast<size_t>(i)], floor_r));
    }
  }
  const double top = *std::max_element(logw.begin(), logw.end());
  std::vector<double> w(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) w[static_cast<size_t>(i)] = std::exp(logw[static_cast<size_t>(i)] - top);
  // Normalise to mean 1, cap, and repeat until the capped weights have mean 1 (a few passes).
  for (int pass = 0; pass < 20; ++pass) {
    const double mean = std::accumulate(w.begin(), w.end(), 0.0) / n;
    bool capped = false;
    for (double& x : w) {
      x /= mean;
      if (x > cap) x = cap, capped = true;
    }
    if (!capped) break;
  }
  return w;
}

std::vector<double> cumulative_weights(const std::vector<double>& weights) {
  std::vector<double> c(weights.size());
  std::partial_sum(weights.begin(), weights.end(), c.begin());
  return c;
}

uint32_t draw_weighted(const std::vector<double>& cumulative, double u) {
  const double target = u * cumulative.back();
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), target);
  const auto i = static_cast<size_t>(it - cumulative.begin());
  return static_cast<uint32_t>(std::min(i, cumulative.size() - 1));
}

}  // namespace curio::online
