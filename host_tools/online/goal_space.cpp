#include "host_tools/online/goal_space.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "host_tools/vae/evaluate.hpp"
#include "host_tools/vae/scene_set.hpp"
#include "sim/scene.hpp"

namespace curio::online {

bool ball_moved(const Scene& s) {
  return std::abs(s[0] - sim::kBallStart.x) > 1e-3 || std::abs(s[1] - sim::kBallStart.y) > 1e-3;
}

train::SceneSet scene_set_of(const std::vector<Scene>& scenes, int threads) {
  auto f = torch::empty({static_cast<int64_t>(scenes.size()), 4}, torch::kFloat32);
  float* p = f.data_ptr<float>();
  for (const Scene& s : scenes) p = std::copy(s.begin(), s.end(), p);
  return train::render_scenes(f, threads);
}

torch::Tensor render_images(const std::vector<Scene>& scenes, int threads) {
  return scene_set_of(scenes, threads).images;
}

EncodedScenes encode_images(train::Vae& model, const torch::Tensor& images_u8, bool with_recon) {
  model->eval();
  const train::Encoded e = train::encode_all(model, images_u8, with_recon);
  EncodedScenes out;
  if (with_recon && e.recon_each.defined())
    out.recon.assign(e.recon_each.data_ptr<double>(), e.recon_each.data_ptr<double>() + e.recon_each.numel());
  const auto mu = e.mu.to(torch::kFloat32).contiguous();
  out.mu.assign(mu.data_ptr<float>(), mu.data_ptr<float>() + mu.numel());
  if (e.mu.size(0) > 0) {
    const auto mu64 = e.mu.to(torch::kFloat64);
    const auto mean = mu64.mean(0).contiguous();
    const auto sd = mu64.std(0, /*unbiased=*/false).contiguous();
    std::copy(mean.data_ptr<double>(), mean.data_ptr<double>() + 10, out.mu_mean.begin());
    std::copy(sd.data_ptr<double>(), sd.data_ptr<double>() + 10, out.mu_sd.begin());
  }
  const std::vector<double> kl = train::mean_kl(e);
  std::copy(kl.begin(), kl.end(), out.kl.begin());
  std::array<int, 10> idx{};
  std::iota(idx.begin(), idx.end(), 0);
  std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) {
    return out.kl[static_cast<size_t>(a)] > out.kl[static_cast<size_t>(b)];
  });
  for (size_t i = 0; i < 10; ++i) out.kl_order[i] = static_cast<uint8_t>(idx[i]);
  return out;
}

std::array<uint8_t, 10> group_order(const std::array<double, 10>& kl, int group_size) {
  if (group_size < 1 || 10 % group_size != 0) throw std::runtime_error("group size must divide 10");
  const int groups = 10 / group_size;
  std::vector<int> g(static_cast<size_t>(groups));
  std::iota(g.begin(), g.end(), 0);
  auto group_kl = [&](int k) {
    double s = 0.0;
    for (int j = 0; j < group_size; ++j) s += kl[static_cast<size_t>(k * group_size + j)];
    return s;
  };
  std::stable_sort(g.begin(), g.end(), [&](int a, int b) { return group_kl(a) > group_kl(b); });
  std::array<uint8_t, 10> order{};
  size_t i = 0;
  for (int k : g) {
    std::array<int, 10> in{};
    std::iota(in.begin(), in.begin() + group_size, k * group_size);
    std::stable_sort(in.begin(), in.begin() + group_size, [&](int a, int b) {
      return kl[static_cast<size_t>(a)] > kl[static_cast<size_t>(b)];
    });
    for (int j = 0; j < group_size; ++j) order[i++] = static_cast<uint8_t>(in[static_cast<size_t>(j)]);
  }
  return order;
}

void encode_scene(train::Vae& model, const Scene& scene, float out[kLatentDim], double* recon_bce) {
  model->eval();
  const train::Encoded e = train::encode_all(model, render_images({scene}, 1), recon_bce != nullptr);
  const auto mu = e.mu.to(torch::kFloat32).contiguous();
  std::copy(mu.data_ptr<float>(), mu.data_ptr<float>() + kLatentDim, out);
  if (recon_bce != nullptr) *recon_bce = e.recon_each.data_ptr<double>()[0];
}

ExplorerConfig goal_space_config(const ExplorerConfig& base, const std::array<uint8_t, 10>& order,
                                 int group_size) {
  ExplorerConfig c = base;
  if (set_latent_modules(c, order.data(), group_size) != Status::kOk)
    throw std::runtime_error("invalid KL order or group size for the goal modules");
  return c;
}

std::vector<float> carried_progress(const Explorer& explorer, const ExplorerConfig& next) {
  std::array<float, kLatentDim> latent_cp;
  latent_cp.fill(InterestModel::kInitialProgress);
  for (int k = 0; k < explorer.n_modules(); ++k) {
    const GoalModule& m = explorer.goal_module(k);
    for (int j = 0; j < m.n_dims; ++j)
      latent_cp[m.dims[j]] = explorer.interest_model().progress(k);
  }
  std::vector<float> cp(static_cast<size_t>(next.n_modules));
  for (int k = 0; k < next.n_modules; ++k) {
    double s = 0.0;
    for (int j = 0; j < next.modules[k].n_dims; ++j) s += latent_cp[next.modules[k].dims[j]];
    cp[static_cast<size_t>(k)] = static_cast<float>(s / next.modules[k].n_dims);
  }
  return cp;
}

std::vector<std::vector<int>> module_latents(const ExplorerConfig& config) {
  std::vector<std::vector<int>> out;
  for (int k = 0; k < config.n_modules; ++k) {
    std::vector<int> l;
    for (int j = 0; j < config.modules[k].n_dims; ++j) l.push_back(config.modules[k].dims[j]);
    out.push_back(l);
  }
  return out;
}

}  // namespace curio::online
