#include "host_tools/online/online_training.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <numeric>

#include <fmt/format.h>

#include "firmware/explore/prng.hpp"
#include "host_tools/vae/checkpoint.hpp"
#include "host_tools/vae/evaluate.hpp"
#include "host_tools/vae/scene_set.hpp"

namespace curio::online {
namespace {

train::Vae seeded_model(const OnlineOptions& o) {
  torch::manual_seed(o.seed);
  train::Vae m;
  m->kaiming_init(o.out_init_scale);
  return m;
}

train::Recipe recipe_of(const OnlineOptions& o, int64_t images) {
  train::Recipe r;
  r.model = "beta-vae";
  r.beta = o.beta;
  r.capacity_max = o.capacity_max;
  r.capacity_iters = o.capacity_iters;
  r.batch = o.batch;
  r.lr = o.lr;
  r.seed = o.seed;
  r.out_init_scale = o.out_init_scale;
  r.dataset_size = images;
  r.scenes_file = "(online: the agent's final scenes, scenes.csv)";
  return r;
}

}  // namespace

OnlineVae::OnlineVae(const OnlineOptions& options)
    : o_(options),
      model_(seeded_model(options)),
      optimizer_(model_->parameters(), torch::optim::AdamOptions(options.lr)) {
  if (o_.progressive()) {
    // Before the first training nothing is open; train() opens the first groups.
    held_.fill(true);
    model_->hold_latents(held_);
  }
}

std::vector<uint32_t> worst_reconstructed(const std::vector<double>& errors, size_t k) {
  std::vector<uint32_t> idx(errors.size());
  std::iota(idx.begin(), idx.end(), 0u);
  k = std::min(k, idx.size());
  std::partial_sort(idx.begin(), idx.begin() + static_cast<std::ptrdiff_t>(k), idx.end(),
                    [&](uint32_t a, uint32_t b) { return errors[a] > errors[b] || (errors[a] == errors[b] && a < b); });
  idx.resize(k);
  return idx;
}

int OnlineVae::open_latents() const {
  return static_cast<int>(std::count(held_.begin(), held_.end(), false));
}

double OnlineVae::capacity_at(int64_t it) const {
  return o_.capacity_max * std::min(1.0, static_cast<double>(it) / static_cast<double>(o_.capacity_iters));
}

TrainingStats OnlineVae::train(const torch::Tensor& images_u8, int64_t iterations, int round,
                               const std::function<void(const std::string&)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  model_->train();
  torch::manual_seed(o_.seed * 1000 + static_cast<uint64_t>(round));
  Prng rng(o_.seed, 1000 + static_cast<uint64_t>(round));
  const auto n = static_cast<uint32_t>(images_u8.size(0));
  TrainingStats st;
  const bool progressive = o_.progressive();
  torch::Tensor anchor_mu, anchor_logvar, anchor_mask;  // [N,10], [N,10], [10] (1: anchored)
  if (progressive) {
    const int open = o_.open_latents_at(capacity_at(iteration_ + iterations));
    train::LatentMask opening{};
    bool any = false;
    for (int l = 0; l < open; ++l)
      if (held_[static_cast<size_t>(l)]) opening[static_cast<size_t>(l)] = any = true;
    if (any && o_.anchor_weight > 0.0 && open_latents() > 0) {
      // The code before any latent opens (fresh read-out weights leave the old ones alone,
      // but the encoder is taken as it is now).
      model_->eval();
      const train::Encoded before = train::encode_all(model_, images_u8);
      model_->train();
      anchor_mu = before.mu;
      anchor_logvar = before.logvar;
      anchor_mask = torch::zeros({10});
      for (size_t l = 0; l < 10; ++l)
        if (!held_[l]) anchor_mask[static_cast<int64_t>(l)] = 1.0f, ++st.anchored;
      if (progress)
        progress(fmt::format("  train {}: anchoring the {} open latents to their code (weight {})", round,
                             st.anchored, o_.anchor_weight));
    }
    if (any) {
      // The first groups start as the recipe's step 1 (KL ≈ 0), later ones as its step 2.
      model_->release_latents(opening, open_latents() == 0 ? o_.out_init_scale : o_.release_scale);
      for (int l = 0; l < open; ++l) held_[static_cast<size_t>(l)] = false;
      if (progress) progress(fmt::format("  train {}: {} latents open (z0..z{})", round, open, open - 1));
    }
  }
  auto index = torch::empty({o_.batch}, torch::kInt64);
  struct Losses { double recon = 0, kl = 0, anchor = 0; };
  std::deque<Losses> window;  // the last 100 iterations
  const auto window_mean = [&window] {
    Losses m;
    for (const Losses& l : window) m.recon += l.recon, m.kl += l.kl, m.anchor += l.anchor;
    const auto n = static_cast<double>(std::max<size_t>(1, window.size()));
    return Losses{m.recon / n, m.kl / n, m.anchor / n};
  };
  for (int64_t i = 0; i < iterations; ++i) {
    int64_t* p = index.data_ptr<int64_t>();
    for (int64_t b = 0; b < o_.batch; ++b) p[b] = rng.below(n);
    const auto x = train::gather_images(images_u8, index);
    const double c = capacity_at(iteration_);
    auto [mu, logvar] = model_->enc->forward(x);
    const auto z = mu + torch::randn_like(mu) * (0.5 * logvar).exp();
    const auto recon = torch::binary_cross_entropy_with_logits(model_->dec->forward(z), x, {}, {},
                                                               at::Reduction::Sum) /
                       static_cast<double>(o_.batch);
    const auto kl = train::kl_per_latent(mu, logvar).sum();
    const auto excess = kl - c;
    auto loss = recon + o_.beta * excess.abs();
    double anchor_kl = 0.0;
    if (anchor_mask.defined()) {
      // KL(N(μ, σ²) ‖ N(μ₀, σ₀²)) per latent, summed over the anchored ones, mean over the batch.
      const auto mu0 = anchor_mu.index_select(0, index);
      const auto lv0 = anchor_logvar.index_select(0, index);
      const auto d = 0.5 * (lv0 - logvar + (logvar.exp() + (mu - mu0).pow(2)) / lv0.exp() - 1.0);
      const auto anchor = (d * anchor_mask).sum() / static_cast<double>(o_.batch);
      loss = loss + o_.anchor_weight * anchor;
      anchor_kl = anchor.item<double>();
    }
    optimizer_.zero_grad();
    loss.backward();
    if (progressive) model_->mask_held_gradients(held_);
    optimizer_.step();
    ++iteration_;
    window.push_back({recon.item<double>(), kl.item<double>(), anchor_kl});
    if (window.size() > 100) window.pop_front();
    st.capacity = c;
    if (progress && ((i + 1) % 500 == 0 || i + 1 == iterations)) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const Losses m = window_mean();
      progress(fmt::format("  train {}: it {}/{} (global {}) | {:.1f} it/s | recon {:.1f} kl {:.2f} C {:.2f}{}",
                           round, i + 1, iterations, iteration_, static_cast<double>(i + 1) / s, m.recon, m.kl, c,
                           anchor_mask.defined() ? fmt::format(" | anchor KL {:.3f}", m.anchor) : ""));
    }
  }
  const Losses m = window_mean();
  st.recon = m.recon;
  st.kl = m.kl;
  st.anchor_kl = m.anchor;
  st.iterations = iterations;
  st.open_latents = open_latents();
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return st;
}

void OnlineVae::save(const std::string& path, int64_t images) {
  train::save_checkpoint(path, model_, optimizer_, recipe_of(o_, images), iteration_);
}

void OnlineVae::load(const std::string& path) {
  iteration_ = train::load_checkpoint(path, model_, &optimizer_).iteration;
  if (o_.progressive()) held_ = model_->held_latents();
}

}  // namespace curio::online
