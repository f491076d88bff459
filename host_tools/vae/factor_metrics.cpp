#include "host_tools/vae/factor_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace curio::train {

double pearson(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) throw std::invalid_argument("pearson: sizes differ");
  const auto n = static_cast<double>(a.size());
  if (a.empty()) return 0.0;
  double ma = 0.0, mb = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    ma += a[i];
    mb += b[i];
  }
  ma /= n;
  mb /= n;
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double da = a[i] - ma, db = b[i] - mb;
    sab += da * db;
    saa += da * da;
    sbb += db * db;
  }
  if (saa <= 0.0 || sbb <= 0.0) return 0.0;
  return sab / std::sqrt(saa * sbb);
}

std::vector<int> discretize(std::span<const double> v, int bins, double lo, double hi) {
  if (bins < 1 || !(hi > lo)) throw std::invalid_argument("discretize: bad bins or range");
  std::vector<int> out(v.size());
  const double width = (hi - lo) / bins;
  for (size_t i = 0; i < v.size(); ++i) {
    const auto b = static_cast<long>(std::floor((v[i] - lo) / width));
    out[i] = static_cast<int>(std::clamp<long>(b, 0, bins - 1));
  }
  return out;
}

std::vector<int> discretize_to_range(std::span<const double> v, int bins) {
  if (v.empty()) return {};
  const auto [mn, mx] = std::minmax_element(v.begin(), v.end());
  if (!(*mx > *mn)) return std::vector<int>(v.size(), 0);
  return discretize(v, bins, *mn, *mx);
}

double entropy(std::span<const int> labels, int bins) {
  std::vector<double> count(static_cast<size_t>(bins), 0.0);
  for (int l : labels) count.at(static_cast<size_t>(l)) += 1.0;
  const auto n = static_cast<double>(labels.size());
  double h = 0.0;
  for (double c : count)
    if (c > 0.0) h -= (c / n) * std::log(c / n);
  return h;
}

double mutual_information(std::span<const int> a, int bins_a, std::span<const int> b,
                          int bins_b) {
  if (a.size() != b.size()) throw std::invalid_argument("mutual_information: sizes differ");
  const auto na = static_cast<size_t>(bins_a), nb = static_cast<size_t>(bins_b);
  std::vector<double> joint(na * nb, 0.0), pa(na, 0.0), pb(nb, 0.0);
  for (size_t i = 0; i < a.size(); ++i) {
    const auto ia = static_cast<size_t>(a[i]), ib = static_cast<size_t>(b[i]);
    joint.at(ia * nb + ib) += 1.0;
    pa.at(ia) += 1.0;
    pb.at(ib) += 1.0;
  }
  const auto n = static_cast<double>(a.size());
  double mi = 0.0;
  for (size_t i = 0; i < na; ++i)
    for (size_t j = 0; j < nb; ++j) {
      const double c = joint[i * nb + j];
      if (c > 0.0) mi += (c / n) * std::log(c * n / (pa[i] * pb[j]));
    }
  return std::max(0.0, mi);
}

MigResult mutual_information_gap(const std::vector<std::vector<double>>& latents,
                                 const std::vector<std::vector<double>>& factors,
                                 const MigOptions& options) {
  MigResult r;
  std::vector<std::vector<int>> zl, fl;
  for (const auto& z : latents) zl.push_back(discretize_to_range(z, options.bins));
  for (const auto& f : factors)
    fl.push_back(discretize(f, options.bins, options.factor_lo, options.factor_hi));
  r.normalized_mi.assign(latents.size(), std::vector<double>(factors.size(), 0.0));
  for (size_t k = 0; k < factors.size(); ++k) {
    const double h = entropy(fl[k], options.bins);
    std::vector<double> column;
    for (size_t l = 0; l < latents.size(); ++l) {
      const double mi = h > 0.0 ? mutual_information(zl[l], options.bins, fl[k], options.bins) / h
                                : 0.0;
      r.normalized_mi[l][k] = mi;
      column.push_back(mi);
    }
    std::sort(column.begin(), column.end(), std::greater<>());
    const double top = column.empty() ? 0.0 : column[0];
    const double second = column.size() < 2 ? 0.0 : column[1];
    r.gap_per_factor.push_back(top - second);
  }
  for (double g : r.gap_per_factor) r.mig += g;
  if (!r.gap_per_factor.empty()) r.mig /= static_cast<double>(r.gap_per_factor.size());
  return r;
}

}  // namespace curio::train
