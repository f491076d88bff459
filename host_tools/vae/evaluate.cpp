#include "host_tools/vae/evaluate.hpp"

namespace curio::train {

Encoded encode_all(Vae& model, const torch::Tensor& images_u8, bool with_recon) {
  torch::NoGradGuard no_grad;
  const int64_t n = images_u8.size(0);
  constexpr int64_t kChunk = 250;
  std::vector<torch::Tensor> mus, logvars, each;
  double recon_sum = 0.0;
  for (int64_t i = 0; i < n; i += kChunk) {
    const auto x = to_float(images_u8.narrow(0, i, std::min(kChunk, n - i)));
    auto [mu, logvar] = model->enc->forward(x);
    mus.push_back(mu);
    logvars.push_back(logvar);
    if (with_recon) {
      const auto logits = model->dec->forward(mu);
      // The mean keeps its own Sum reduction, so reported figures stay as they were.
      recon_sum += torch::binary_cross_entropy_with_logits(logits, x, {}, {}, at::Reduction::Sum)
                       .item<double>();
      each.push_back(torch::binary_cross_entropy_with_logits(logits, x, {}, {}, at::Reduction::None)
                         .sum({1, 2, 3})
                         .to(torch::kFloat64));
    }
  }
  Encoded e{torch::cat(mus), torch::cat(logvars), 0.0, {}};
  if (with_recon && n > 0) {
    e.recon = recon_sum / static_cast<double>(n);
    e.recon_each = torch::cat(each).contiguous();
  }
  return e;
}

std::vector<double> mean_kl(const Encoded& e) {
  const auto kl = kl_per_latent(e.mu, e.logvar).to(torch::kFloat64).contiguous();
  return {kl.data_ptr<double>(), kl.data_ptr<double>() + kl.numel()};
}

std::vector<std::vector<double>> columns(const torch::Tensor& t) {
  const auto d = t.to(torch::kFloat64).t().contiguous();
  std::vector<std::vector<double>> out;
  for (int64_t k = 0; k < d.size(0); ++k) {
    const double* p = d[k].data_ptr<double>();
    out.emplace_back(p, p + d.size(1));
  }
  return out;
}

FactorReport evaluate_factors(Vae& model, const std::string& model_kind, const SceneSet& set,
                              const Criteria& criteria, double* recon) {
  const Encoded e = encode_all(model, set.images, recon != nullptr);
  if (recon) *recon = e.recon;
  return make_factor_report(model_kind, mean_kl(e), columns(e.mu), columns(set.factors),
                            criteria);
}

}  // namespace curio::train
