#include "host_tools/vae/recipe.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace curio::train {
namespace {

double ramp(int64_t done, int64_t length) {
  if (length <= 0) return done >= 0 ? 1.0 : 0.0;
  return std::clamp(static_cast<double>(done) / static_cast<double>(length), 0.0, 1.0);
}

}  // namespace

ScheduleAt schedule_at(const Recipe& r, int64_t it) {
  const TrialOptions& t = r.trial;
  ScheduleAt s{1.0, 0.0, r.lr, r.ball_spread};
  if (r.ball_spread_iters > 0) {
    const double spread =
        r.ball_spread + (r.ball_spread_to - r.ball_spread) * ramp(it, r.ball_spread_iters);
    s.ball_spread = std::round(spread / kBallSpreadStep) * kBallSpreadStep;
  }
  if (t.lr_warmup > 0) s.lr = r.lr * std::min(1.0, static_cast<double>(it + 1) / t.lr_warmup);
  if (t.lr_decay_from >= 0 && it >= t.lr_decay_from)
    s.lr = r.lr + (t.lr_final - r.lr) * ramp(it - t.lr_decay_from, r.iterations - t.lr_decay_from);
  if (!r.is_beta_vae() || it < t.warmup) return s;
  if (it >= t.vae_window_from && it < t.vae_window_to) return s;
  const int64_t since = it - t.warmup;
  s.beta = 1.0 + (r.beta - 1.0) * ramp(since, t.beta_ramp);
  s.capacity = r.capacity_min + (r.capacity_max - r.capacity_min) * ramp(since, r.capacity_iters);
  return s;
}

int trained_latents(const Recipe& r, int64_t it) {
  int n = r.latent_stages.empty() ? 10 : r.latent_stages.front().second;
  for (const auto& [from, count] : r.latent_stages)
    if (it >= from) n = count;
  return n;
}

std::vector<std::pair<int64_t, int>> parse_latent_stages(const std::string& text) {
  std::vector<std::pair<int64_t, int>> stages;
  size_t pos = 0;
  if (!text.empty() && text.back() == ',')
    throw std::invalid_argument("latent stages end with a comma: '" + text + "'");
  while (pos < text.size()) {
    const size_t end = std::min(text.find(',', pos), text.size());
    const std::string item = text.substr(pos, end - pos);
    const size_t colon = item.find(':');
    if (colon == std::string::npos)
      throw std::invalid_argument("latent stage '" + item + "' is not ITERATION:COUNT");
    size_t used_it = 0, used_n = 0;
    int64_t it = 0;
    int n = 0;
    try {
      it = std::stoll(item.substr(0, colon), &used_it);
      n = std::stoi(item.substr(colon + 1), &used_n);
    } catch (const std::exception&) {
      throw std::invalid_argument("latent stage '" + item + "' is not ITERATION:COUNT");
    }
    if (used_it != colon || used_n != item.size() - colon - 1)
      throw std::invalid_argument("latent stage '" + item + "' is not ITERATION:COUNT");
    if (it < 0 || n < 1 || n > 10)
      throw std::invalid_argument("latent stage '" + item + "': need iteration ≥ 0, count 1..10");
    if (!stages.empty() && it <= stages.back().first)
      throw std::invalid_argument("latent stages must have increasing iterations");
    stages.emplace_back(it, n);
    pos = end + 1;
  }
  if (!stages.empty() && stages.front().first != 0)
    throw std::invalid_argument("the first latent stage must start at iteration 0");
  return stages;
}

nlohmann::json to_json(const Recipe& r) {
  nlohmann::json j = {{"model", r.model},
                      {"beta", r.is_beta_vae() ? r.beta : 1.0},
                      {"capacity_min", r.is_beta_vae() ? r.capacity_min : 0.0},
                      {"capacity_max", r.is_beta_vae() ? r.capacity_max : 0.0},
                      {"capacity_iters", r.capacity_iters},
                      {"iterations", r.iterations},
                      {"batch", r.batch},
                      {"lr", r.lr},
                      {"latent_stages", r.latent_stages},
                      {"out_init_scale", r.out_init_scale},
                      {"init_from", r.init_from},
                      {"dataset_size", r.dataset_size},
                      {"seed", r.seed},
                      {"ball_spread", r.ball_spread},
                      {"ball_spread_to", r.ball_spread_to},
                      {"ball_spread_iters", r.ball_spread_iters},
                      {"scenes_file", r.scenes_file}};
  add_to_json(r.trial, j);
  return j;
}

// Keys read with j.at() were in the first recipe.json; the others default when absent.
Recipe recipe_from_json(const nlohmann::json& j) {
  Recipe r;
  r.model = j.at("model").get<std::string>();
  r.beta = j.at("beta").get<double>();
  r.capacity_min = j.value("capacity_min", 0.0);
  r.capacity_max = j.at("capacity_max").get<double>();
  r.capacity_iters = j.at("capacity_iters").get<int64_t>();
  r.iterations = j.at("iterations").get<int64_t>();
  r.batch = j.at("batch").get<int64_t>();
  r.lr = j.at("lr").get<double>();
  if (j.contains("latent_stages"))
    r.latent_stages = j.at("latent_stages").get<std::vector<std::pair<int64_t, int>>>();
  r.out_init_scale = j.value("out_init_scale", 1.0);
  r.init_from = j.value("init_from", std::string{});
  r.dataset_size = j.at("dataset_size").get<int64_t>();
  r.seed = j.at("seed").get<uint64_t>();
  r.ball_spread = j.value("ball_spread", 1.0);
  r.ball_spread_to = j.value("ball_spread_to", 1.0);
  r.ball_spread_iters = j.value("ball_spread_iters", int64_t{0});
  r.scenes_file = j.value("scenes_file", std::string{});
  r.trial = trial_options_from_json(j);
  return r;
}

}  // namespace curio::train
