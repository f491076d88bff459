#include "host_tools/encode/encode_images.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "firmware/nn/encoder.hpp"
#include "host_tools/experiment/algorithms.hpp"
#include "host_tools/experiment/batch_encode.hpp"
#include "host_tools/model_io/float_model.hpp"

namespace curio::encode {
namespace {

namespace fs = std::filesystem;

constexpr int kTile = nn::kImageSize;
constexpr int kSteps = 7;  // traversal values −3, −2, …, 3
constexpr int kGap = 8;    // pixels between the reconstruction and the traversals, and blocks

// Module indices by decreasing activity (ties: lower index first).
std::vector<size_t> modules_by_activity(const ImageCodes& c) {
  std::vector<size_t> order(c.module_activity.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&c](size_t a, size_t b) { return c.module_activity[a] > c.module_activity[b]; });
  return order;
}

std::string algorithm_for(const std::string& representation) {
  return representation == "vae" ? "MGE-VAE" : "MGE-βVAE";
}

}  // namespace

GoalSpace::GoalSpace(const std::string& name, const std::string& models_dir) {
  rep_ = lab::find_representation(name);
  if (rep_ == nullptr) {
    std::string known;
    for (const auto& n : lab::available_representations()) known += (known.empty() ? "" : ", ") + n;
    throw std::runtime_error(fmt::format("--weights {}: this build has no such weights (known: {})", name,
                                         known.empty() ? "none" : known));
  }
  const auto algo = lab::find_algorithm(algorithm_for(name));
  ExplorerConfig config;
  if (!algo || lab::configure_modules(*algo, config, rep_->kl_order.data()) != Status::kOk)
    throw std::runtime_error("cannot group the latents into goal modules");
  for (int k = 0; k < config.n_modules; ++k) {
    std::vector<int> dims;
    for (int j = 0; j < config.modules[k].n_dims; ++j) dims.push_back(config.modules[k].dims[j]);
    modules_.push_back(dims);
  }
  encoder_ = std::make_unique<nn::Encoder>(*rep_->model);
  float_path_ = (fs::path(models_dir) / (name + ".cfm")).string();
  try {
    const model_io::FloatModel model = model_io::read_float_model(float_path_);
    float_encoder_.emplace(model);
    try {
      decoder_.emplace(model);
    } catch (const std::exception& e) {
      float_note_ = std::string("no decoder in the float model: ") + e.what();
    }
  } catch (const std::exception& e) {
    float_note_ = std::string("no float model: ") + e.what();
  }
}

ImageCodes GoalSpace::encode(const CameraImage& image) const {
  ImageCodes c;
  c.image = image;
  if (encoder_->encode(image.frame.data(), c.mu_int8.data(), c.log_var_int8.data()) != nn::Status::kOk)
    throw std::runtime_error(image.path + ": the int8 encoder refused its weights (a corrupt header?)");
  complete(&c);
  return c;
}

std::vector<ImageCodes> GoalSpace::encode_all(const std::vector<CameraImage>& images, int threads) const {
  std::vector<uint8_t> frames(images.size() * static_cast<size_t>(nn::kImageBytes));
  for (size_t i = 0; i < images.size(); ++i)
    std::copy(images[i].frame.begin(), images[i].frame.end(), frames.begin() + static_cast<std::ptrdiff_t>(i * nn::kImageBytes));
  std::vector<float> mu(images.size() * kLatents), log_var(images.size() * kLatents);
  const std::string error = lab::encode_frames(*rep_->model, frames.data(), static_cast<int32_t>(images.size()),
                                               threads, mu.data(), log_var.data());
  if (!error.empty()) throw std::runtime_error(error);
  std::vector<ImageCodes> codes(images.size());
  for (size_t i = 0; i < images.size(); ++i) {
    codes[i].image = images[i];
    std::copy_n(mu.begin() + static_cast<std::ptrdiff_t>(i * kLatents), kLatents, codes[i].mu_int8.begin());
    std::copy_n(log_var.begin() + static_cast<std::ptrdiff_t>(i * kLatents), kLatents, codes[i].log_var_int8.begin());
    complete(&codes[i]);
  }
  return codes;
}

void GoalSpace::complete(ImageCodes* c) const {
  if (float_encoder_) {
    std::array<float, nn::kImageBytes> pixels{};
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<float>(c->image.frame[i]) / 255.0f;
    model_io::EncoderTrace trace;
    float_encoder_->forward(pixels.data(), &trace);
    for (int j = 0; j < kLatents; ++j) {
      c->mu_float[static_cast<size_t>(j)] = trace.out[static_cast<size_t>(j)];
      c->log_var_float[static_cast<size_t>(j)] = trace.out[static_cast<size_t>(kLatents + j)];
    }
    c->has_float = true;
  }
  for (size_t j = 0; j < kLatents; ++j) {
    const double mu = c->mu_int8[j], lv = c->log_var_int8[j];
    c->kl[j] = static_cast<float>(0.5 * (mu * mu + std::exp(lv) - lv - 1.0));
  }
  c->module_activity.clear();
  for (const auto& m : modules_) {
    double a = 0.0;
    for (int l : m) a += c->kl[static_cast<size_t>(l)];
    c->module_activity.push_back(a);
  }
}

std::vector<float> GoalSpace::decode(const Latents& z) const {
  return decoder_->image(z);
}

std::string codes_csv(const GoalSpace& space, const std::vector<ImageCodes>& codes) {
  std::ostringstream f;
  f << "file,latent,kl_rank,kl_training_nats,module,mu_int8,log_var_int8,mu_float,log_var_float,"
       "mu_int8_minus_float,kl_image_nats\n";
  const auto& rep = space.representation();
  std::array<int, kLatents> module_of{};
  for (size_t k = 0; k < space.modules().size(); ++k)
    for (int l : space.modules()[k]) module_of[static_cast<size_t>(l)] = static_cast<int>(k);
  for (const ImageCodes& c : codes) {
    for (int rank = 0; rank < kLatents; ++rank) {
      const size_t l = rep.kl_order[static_cast<size_t>(rank)];
      f << '"' << c.image.path << "\",z" << l << ',' << rank << ',' << fmt::format("{:.4f}", rep.kl_per_latent[l]) << ','
        << module_of[l] << ',' << fmt::format("{:.6f},{:.6f}", c.mu_int8[l], c.log_var_int8[l]);
      if (c.has_float) {
        f << fmt::format(",{:.6f},{:.6f},{:.6f}", c.mu_float[l], c.log_var_float[l], c.mu_int8[l] - c.mu_float[l]);
      } else {
        f << ",,,";
      }
      f << fmt::format(",{:.6f}\n", c.kl[l]);
    }
  }
  return f.str();
}

nlohmann::json codes_json(const GoalSpace& space, const std::vector<ImageCodes>& codes,
                          const std::vector<std::pair<std::string, std::string>>& refused) {
  const auto& rep = space.representation();
  nlohmann::json j;
  j["model"] = rep.name;
  j["weights_inputs_sha256"] = rep.inputs_sha256;
  j["kl_order"] = std::vector<int>(rep.kl_order.begin(), rep.kl_order.end());
  j["kl_per_latent_nats"] = std::vector<float>(rep.kl_per_latent.begin(), rep.kl_per_latent.end());
  j["goal_modules"] = space.modules();
  j["float_model"] = space.has_float() ? nlohmann::json(space.float_model_path()) : nlohmann::json(nullptr);
  if (!space.float_note().empty()) j["float_model_note"] = space.float_note();
  j["images"] = nlohmann::json::array();
  for (const ImageCodes& c : codes) {
    nlohmann::json e;
    e["file"] = c.image.path;
    e["size"] = {c.image.source_width, c.image.source_height};
    e["resized"] = c.image.resized;
    e["mu_int8"] = std::vector<float>(c.mu_int8.begin(), c.mu_int8.end());
    e["log_var_int8"] = std::vector<float>(c.log_var_int8.begin(), c.log_var_int8.end());
    if (c.has_float) {
      e["mu_float"] = std::vector<float>(c.mu_float.begin(), c.mu_float.end());
      e["log_var_float"] = std::vector<float>(c.log_var_float.begin(), c.log_var_float.end());
      float worst = 0.0f;
      for (int l = 0; l < kLatents; ++l) worst = std::max(worst, std::abs(c.mu_int8[static_cast<size_t>(l)] - c.mu_float[static_cast<size_t>(l)]));
      e["max_abs_mu_int8_minus_float"] = worst;
    }
    e["kl_image_nats"] = std::vector<float>(c.kl.begin(), c.kl.end());
    const std::vector<size_t> order = modules_by_activity(c);
    e["modules_by_activity"] = order;
    e["module_activity_nats"] = c.module_activity;
    j["images"].push_back(e);
  }
  j["refused"] = nlohmann::json::array();
  for (const auto& [file, why] : refused) j["refused"].push_back({{"file", file}, {"error", why}});
  return j;
}

Figure codes_figure(const GoalSpace& space, const std::vector<ImageCodes>& codes, int max_images) {
  constexpr int kPitch = kTile + 2;  // tiles 2 grey pixels apart
  Figure fig;
  const int n = std::min<int>(max_images, static_cast<int>(codes.size()));
  const int block_h = 4 * kPitch;
  fig.width = (2 + kSteps) * kPitch + kGap;
  fig.height = n * block_h + (n > 0 ? (n - 1) * kGap : 0);
  fig.hwc.assign(static_cast<size_t>(fig.width) * static_cast<size_t>(fig.height) * 3, 0.25f);  // grey
  auto put = [&fig](const std::vector<float>& tile, int x0, int y0) {
    for (int y = 0; y < kTile; ++y)
      for (int x = 0; x < kTile; ++x)
        for (int ch = 0; ch < 3; ++ch)
          fig.hwc[(static_cast<size_t>(y0 + y) * static_cast<size_t>(fig.width) + static_cast<size_t>(x0 + x)) * 3 + static_cast<size_t>(ch)] =
              tile[(static_cast<size_t>(y) * kTile + static_cast<size_t>(x)) * 3 + static_cast<size_t>(ch)];
  };
  for (int i = 0; i < n; ++i) {
    const ImageCodes& c = codes[static_cast<size_t>(i)];
    const int y0 = i * (block_h + kGap);
    std::vector<float> input(nn::kImageBytes);
    for (size_t k = 0; k < input.size(); ++k) input[k] = static_cast<float>(c.image.frame[k]) / 255.0f;
    put(input, 0, y0);
    const Latents& mu = c.has_float ? c.mu_float : c.mu_int8;
    put(space.decode(mu), kPitch, y0);
    const std::vector<size_t> order = modules_by_activity(c);
    int row = 0;
    for (size_t m = 0; m < 2 && m < order.size(); ++m) {
      for (int l : space.modules()[order[m]]) {
        if (row >= 4) break;
        for (int s = 0; s < kSteps; ++s) {
          Latents z = mu;
          z[static_cast<size_t>(l)] = -3.0f + 6.0f * static_cast<float>(s) / (kSteps - 1);
          put(space.decode(z), 2 * kPitch + kGap + s * kPitch, y0 + row * kPitch);
        }
        ++row;
      }
    }
  }
  return fig;
}

}  // namespace curio::encode
