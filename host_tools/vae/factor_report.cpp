#include "host_tools/vae/factor_report.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include <fmt/format.h>

namespace curio::train {

FactorReport make_factor_report(const std::string& model, const std::vector<double>& kl_per_latent,
                                const std::vector<std::vector<double>>& mu,
                                const std::vector<std::vector<double>>& factors,
                                const Criteria& criteria) {
  FactorReport r;
  r.model = model;
  r.images = mu.empty() ? 0 : static_cast<int>(mu[0].size());
  r.kl_per_latent = kl_per_latent;
  const size_t latents = mu.size();
  r.corr.assign(latents, std::vector<double>(factors.size(), 0.0));
  r.best_factor.assign(latents, 0);
  for (size_t l = 0; l < latents; ++l) {
    for (size_t k = 0; k < factors.size(); ++k) r.corr[l][k] = pearson(mu[l], factors[k]);
    double best = -1.0;
    for (size_t k = 0; k < factors.size(); ++k)
      if (std::abs(r.corr[l][k]) > best) {
        best = std::abs(r.corr[l][k]);
        r.best_factor[l] = static_cast<int>(k);
      }
  }
  std::vector<int> order(latents);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return kl_per_latent[a] > kl_per_latent[b]; });
  for (int l : order)
    if (kl_per_latent[l] > criteria.active_kl) r.active.push_back(l);

  r.mig_all = mutual_information_gap(mu, factors);
  std::vector<std::vector<double>> active_mu;
  for (int l : r.active) active_mu.push_back(mu[l]);
  r.mig_active = mutual_information_gap(active_mu, factors);

  const int n_active = static_cast<int>(r.active.size());
  if (model == "beta-vae") {
    if (n_active != criteria.beta_vae_active)
      r.reasons.push_back(fmt::format("{} active latents, want exactly {}", n_active,
                                      criteria.beta_vae_active));
    std::set<int> covered;
    for (int l : r.active) {
      const int k = r.best_factor[l];
      const double own = std::abs(r.corr[l][k]);
      if (own < criteria.own_corr)
        r.reasons.push_back(fmt::format("z{} best |corr| {:.3f} with {} < {}", l, own,
                                        kFactorNames[k], criteria.own_corr));
      else
        covered.insert(k);
      for (size_t j = 0; j < factors.size(); ++j)
        if (static_cast<int>(j) != k && std::abs(r.corr[l][j]) > criteria.other_corr)
          r.reasons.push_back(fmt::format("z{} |corr| {:.3f} with {} > {}", l,
                                          std::abs(r.corr[l][j]), kFactorNames[j],
                                          criteria.other_corr));
    }
    for (int k = 0; k < static_cast<int>(factors.size()); ++k)
      if (!covered.count(k))
        r.reasons.push_back(fmt::format("no clean latent for {}", kFactorNames[k]));
    if (r.mig_all.mig < criteria.beta_vae_mig)
      r.reasons.push_back(fmt::format("MIG {:.3f} < {}", r.mig_all.mig, criteria.beta_vae_mig));
  } else {
    if (n_active < criteria.vae_min_active)
      r.reasons.push_back(fmt::format("{} active latents, want at least {}", n_active,
                                      criteria.vae_min_active));
    if (r.mig_all.mig >= criteria.vae_max_mig)
      r.reasons.push_back(fmt::format("MIG {:.3f} ≥ {}: not entangled", r.mig_all.mig,
                                      criteria.vae_max_mig));
  }
  r.pass = r.reasons.empty();
  return r;
}

nlohmann::json to_json(const FactorReport& r, const Criteria& c) {
  using nlohmann::json;
  json latents = json::array();
  for (size_t l = 0; l < r.corr.size(); ++l) {
    json corr = json::object(), nmi = json::object();
    for (size_t k = 0; k < r.corr[l].size(); ++k) {
      corr[kFactorNames[k]] = r.corr[l][k];
      nmi[kFactorNames[k]] = r.mig_all.normalized_mi[l][k];
    }
    latents.push_back({{"index", l},
                       {"kl", r.kl_per_latent[l]},
                       {"active", r.kl_per_latent[l] > c.active_kl},
                       {"best_factor", kFactorNames[r.best_factor[l]]},
                       {"abs_corr_best", std::abs(r.corr[l][r.best_factor[l]])},
                       {"corr", corr},
                       {"normalized_mi", nmi}});
  }
  json gaps = json::object(), gaps_active = json::object();
  for (size_t k = 0; k < r.mig_all.gap_per_factor.size(); ++k) {
    gaps[kFactorNames[k]] = r.mig_all.gap_per_factor[k];
    gaps_active[kFactorNames[k]] = r.mig_active.gap_per_factor[k];
  }
  return {{"model", r.model},
          {"images", r.images},
          {"factors", kFactorNames},
          {"kl_per_latent", r.kl_per_latent},
          {"active_latents", r.active},
          {"active_count", r.active.size()},
          {"latents", latents},
          {"mig", r.mig_all.mig},
          {"mig_gap_per_factor", gaps},
          {"mig_active_only", r.mig_active.mig},
          {"mig_estimator",
           "plug-in histogram MI: each latent mean discretised into 20 equal-width bins over its "
           "sample range, each factor into 20 equal-width bins over [-1,1]; MI/H(factor); "
           "gap = top minus second latent per factor; MIG = mean gap over the 4 factors"},
          {"criteria",
           {{"active_kl", c.active_kl},
            {"beta_vae_active", c.beta_vae_active},
            {"own_corr", c.own_corr},
            {"other_corr", c.other_corr},
            {"beta_vae_mig", c.beta_vae_mig},
            {"vae_min_active", c.vae_min_active},
            {"vae_max_mig", c.vae_max_mig}}},
          {"pass", r.pass},
          {"reasons", r.reasons}};
}

std::string summary_text(const FactorReport& r) {
  std::string s;
  for (int l : r.active) {
    s += fmt::format("  z{} KL {:5.2f} |", l, r.kl_per_latent[l]);
    for (size_t k = 0; k < r.corr[l].size(); ++k)
      s += fmt::format(" {} {:.2f}", kFactorNames[k], std::abs(r.corr[l][k]));
    s += "\n";
  }
  s += fmt::format("  {} active, MIG {:.3f} (active only {:.3f}) -> {}\n", r.active.size(),
                   r.mig_all.mig, r.mig_active.mig, r.pass ? "PASS" : "FAIL");
  for (const auto& why : r.reasons) s += "    " + why + "\n";
  return s;
}

}  // namespace curio::train
