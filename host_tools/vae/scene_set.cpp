#include "host_tools/vae/scene_set.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "firmware/explore/prng.hpp"
#include "sim/render.hpp"

namespace curio::train {

namespace {

// Renders set.images from set.factors (float32 [N,4]) on `threads` threads.
void render_images(SceneSet& set, int threads) {
  const int64_t n = set.factors.size(0);
  const float* f = set.factors.data_ptr<float>();
  set.images = torch::empty({n, 3, sim::kImageSize, sim::kImageSize}, torch::kUInt8);
  uint8_t* out = set.images.data_ptr<uint8_t>();
  constexpr int64_t kPlane = sim::kImageSize * sim::kImageSize;
  auto work = [&](int64_t begin, int64_t end) {
    sim::Image hwc;
    for (int64_t i = begin; i < end; ++i) {
      const float* p = f + 4 * i;
      sim::render_scene({p[0], p[1]}, {p[2], p[3]}, &hwc);
      uint8_t* img = out + i * 3 * kPlane;
      for (int64_t px = 0; px < kPlane; ++px)
        for (int64_t c = 0; c < 3; ++c) {
          const float v = std::clamp(hwc[static_cast<size_t>(px * 3 + c)], 0.0f, 1.0f);
          img[c * kPlane + px] = static_cast<uint8_t>(std::lround(v * 255.0f));
        }
    }
  };
  const int t = std::max(1, threads);
  std::vector<std::thread> pool;
  for (int k = 0; k < t; ++k) pool.emplace_back(work, n * k / t, n * (k + 1) / t);
  for (auto& th : pool) th.join();
}

constexpr const char* kSceneCsvHeader = "episode,ball_x,ball_y,distractor_x,distractor_y";

// The four positions of one data row, or a message saying what is wrong with it.
bool parse_scene_row(const std::string& line, std::array<float, 4>* out, std::string* why) {
  std::vector<std::string> fields;
  size_t from = 0;
  for (size_t comma; (comma = line.find(',', from)) != std::string::npos; from = comma + 1)
    fields.push_back(line.substr(from, comma - from));
  fields.push_back(line.substr(from));
  if (fields.size() != 5) {
    *why = "expected 5 comma-separated fields, found " + std::to_string(fields.size());
    return false;
  }
  for (size_t k = 1; k < 5; ++k) {
    const std::string& text = fields[k];
    float v = 0.0f;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) {
      *why = "field " + std::to_string(k + 1) + " ('" + text + "') is not a finite number";
      return false;
    }
    (*out)[k - 1] = v;
  }
  return true;
}

}  // namespace

SceneSet render_scene_set(int64_t n, uint64_t seed, uint64_t stream, int threads,
                          double ball_spread) {
  SceneSet set;
  set.factors = torch::empty({n, 4}, torch::kFloat32);
  float* f = set.factors.data_ptr<float>();
  Prng rng(seed, stream);
  for (int64_t i = 0; i < 4 * n; ++i) {
    const double spread = i % 4 < 2 ? ball_spread : 1.0;  // ball x, ball y, distractor x, y
    f[i] = static_cast<float>(spread * rng.uniform(-1.0, 1.0));
  }
  render_images(set, threads);
  return set;
}

SceneSet render_scenes(torch::Tensor factors, int threads) {
  SceneSet set;
  set.factors = factors.to(torch::kFloat32).contiguous();
  render_images(set, threads);
  return set;
}

SceneSet load_scene_set_csv(const std::string& path, int threads) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read scenes file " + path);
  std::string line;
  if (!std::getline(in, line) || line.substr(0, line.find_last_not_of('\r') + 1) != kSceneCsvHeader)
    throw std::runtime_error(path + ":1: expected the header '" + std::string(kSceneCsvHeader) +
                             "' (curio-lab run --save-scenes)");
  std::vector<std::array<float, 4>> rows;
  for (int64_t number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::array<float, 4> row{};
    std::string why;
    if (!parse_scene_row(line, &row, &why))
      throw std::runtime_error(path + ":" + std::to_string(number) + ": " + why);
    rows.push_back(row);
  }
  if (rows.empty()) throw std::runtime_error(path + ": no scenes after the header");
  SceneSet set;
  const auto n = static_cast<int64_t>(rows.size());
  set.factors = torch::empty({n, 4}, torch::kFloat32);
  float* f = set.factors.data_ptr<float>();
  for (const auto& row : rows) f = std::copy(row.begin(), row.end(), f);
  render_images(set, threads);
  return set;
}

torch::Tensor to_float(const torch::Tensor& images_u8) {
  return images_u8.to(torch::kFloat32).div_(255.0);
}

torch::Tensor gather_images(const torch::Tensor& images_u8, const torch::Tensor& index) {
  return to_float(images_u8.index_select(0, index));
}

}  // namespace curio::train
