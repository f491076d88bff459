#include "host_tools/vae/latent_unmixing.hpp"

#include <cmath>
#include <stdexcept>

#include "host_tools/vae/evaluate.hpp"

namespace curio::train {
namespace {

// S^(-1/2) of a symmetric positive-definite matrix.
torch::Tensor inverse_sqrt(const torch::Tensor& s) {
  auto [values, vectors] = torch::linalg_eigh(s);
  return vectors.matmul(torch::diag(values.rsqrt())).matmul(vectors.t());
}

// W ← (W Wᵀ)^(-1/2) W: the nearest orthogonal matrix, treating all rows alike.
torch::Tensor symmetric_decorrelation(const torch::Tensor& w) {
  return inverse_sqrt(w.matmul(w.t())).matmul(w);
}

}  // namespace

FastIcaResult fast_ica(const torch::Tensor& whitened, uint64_t seed, int max_iterations,
                       double tolerance) {
  const auto x = whitened.to(torch::kFloat64);
  const int64_t n = x.size(0), k = x.size(1);
  auto generator = at::detail::createCPUGenerator(seed);
  FastIcaResult r;
  auto w = symmetric_decorrelation(
      torch::randn({k, k}, generator, torch::TensorOptions().dtype(torch::kFloat64)));
  for (int i = 1; i <= max_iterations && !r.converged; ++i) {
    r.iterations = i;
    // Fixed-point step for the log-cosh contrast: w ← E[x g(wᵀx)] − E[g'(wᵀx)] w, g = tanh.
    const auto g = torch::tanh(x.matmul(w.t()));  // [N,k]
    const auto g_prime_mean = (1.0 - g.pow(2)).mean(0);
    auto next = g.t().matmul(x) / static_cast<double>(n) - torch::diag(g_prime_mean).matmul(w);
    next = symmetric_decorrelation(next);
    // Converged when every row points where it pointed before (up to sign).
    const double change =
        (next.matmul(w.t()).diagonal().abs() - 1.0).abs().max().item<double>();
    w = next;
    r.converged = change < tolerance;
  }
  r.unmixing = w;
  return r;
}

UnmixResult unmix_active_latents(Vae& model, const torch::Tensor& images_u8, uint64_t seed,
                                 double active_kl) {
  const Encoded e = encode_all(model, images_u8);
  const std::vector<double> kl = mean_kl(e);
  UnmixResult r;
  for (int l = 0; l < kLatents; ++l)
    if (kl[static_cast<size_t>(l)] > active_kl) r.active.push_back(l);
  const auto k = static_cast<int64_t>(r.active.size());
  if (k < 2)
    throw std::runtime_error("unmix: " + std::to_string(k) +
                             " active latent(s) (KL > " + std::to_string(active_kl) +
                             "); nothing to unmix");
  const auto index = torch::tensor(std::vector<int64_t>(r.active.begin(), r.active.end()));
  const auto mu = e.mu.index_select(1, index).to(torch::kFloat64);          // [N,k]
  const auto logvar = e.logvar.index_select(1, index).to(torch::kFloat64);  // [N,k]
  const int64_t n = mu.size(0);

  r.mean = mu.mean(0);
  const auto centred = mu - r.mean;
  const auto whitening = inverse_sqrt(centred.t().matmul(centred) / static_cast<double>(n - 1));
  r.ica = fast_ica(centred.matmul(whitening), seed);
  r.transform = r.ica.unmixing.matmul(whitening);  // A
  const auto sources = centred.matmul(r.transform.t());
  const auto z = (sources - sources.mean(0)) / sources.std(0);
  const auto kurt = (z.pow(4).mean(0) - 3.0).contiguous();
  r.excess_kurtosis.assign(kurt.data_ptr<double>(), kurt.data_ptr<double>() + k);

  // Write A into the network. μ' = A(μ − m): the μ rows of enc.fc_out. z = A⁻¹z' + m: the
  // columns of dec.fc1, so decoding μ' gives exactly the image that decoding μ gave.
  torch::NoGradGuard no_grad;
  auto& w_out = model->enc->fc_out->weight;  // [20,256]
  auto& b_out = model->enc->fc_out->bias;    // [20]
  auto& w_dec = model->dec->fc1->weight;     // [256,10]
  auto& b_dec = model->dec->fc1->bias;       // [256]
  const auto opts = w_out.options();
  const auto a = r.transform;
  const auto w_mu = w_out.index_select(0, index).to(torch::kFloat64);
  const auto b_mu = b_out.index_select(0, index).to(torch::kFloat64);
  const auto lv_index = index + kLatents;
  const auto w_lv = w_out.index_select(0, lv_index).to(torch::kFloat64);
  const auto b_lv = b_out.index_select(0, lv_index).to(torch::kFloat64);
  const auto w_d = w_dec.index_select(1, index).to(torch::kFloat64);  // [256,k]

  // The posterior variance of z'_i is Σ_j A_ij² σ_j². A linear layer cannot output the log of
  // that sum exactly; use its first-order expansion around the mean log σ² of each latent:
  // log Σ_j c_j e^{l_j} ≈ log Σ_j c_j e^{l̄_j} + Σ_j p_j (l_j − l̄_j), p_j ∝ c_j e^{l̄_j}.
  const auto c = a.pow(2) * logvar.mean(0).exp().unsqueeze(0);  // [k,k]
  const auto p = c / c.sum(1, true);
  const auto new_w_lv = p.matmul(w_lv);
  const auto new_b_lv = c.sum(1).log() + p.matmul(b_lv - logvar.mean(0));

  w_out.index_copy_(0, index, a.matmul(w_mu).to(opts));
  b_out.index_copy_(0, index, a.matmul(b_mu - r.mean).to(opts));
  w_out.index_copy_(0, lv_index, new_w_lv.to(opts));
  b_out.index_copy_(0, lv_index, new_b_lv.to(opts));
  b_dec.add_(w_d.matmul(r.mean).to(opts));
  w_dec.index_copy_(1, index, w_d.matmul(torch::linalg_inv(a)).to(opts));
  return r;
}

}  // namespace curio::train
