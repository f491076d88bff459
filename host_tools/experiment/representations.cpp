#include "host_tools/experiment/representations.hpp"

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#if CURIO_HAVE_BETA_VAE_WEIGHTS
#include "firmware/nn/models/beta_vae_weights.hpp"
#endif
#if CURIO_HAVE_VAE_WEIGHTS
#include "firmware/nn/models/vae_weights.hpp"
#endif

namespace curio::lab {
namespace {

template <typename KlOrder, typename Kl>
Representation make(const char* name, const nn::EncoderModel* model, const KlOrder& order,
                    const Kl& kl, const char* sha) {
  Representation r{name, model, {}, {}, sha};
  for (size_t i = 0; i < 10; ++i) {
    r.kl_order[i] = static_cast<uint8_t>(order[i]);
    r.kl_per_latent[i] = kl[i];
  }
  return r;
}

const std::vector<Representation>& all() {
  static const std::vector<Representation> reps = [] {
    std::vector<Representation> v;
#if CURIO_HAVE_BETA_VAE_WEIGHTS
    v.push_back(make("beta_vae", &nn::beta_vae::kEncoderModel, nn::beta_vae::kKlOrder,
                     nn::beta_vae::kKlPerLatent, nn::beta_vae::kInputsSha256));
#endif
#if CURIO_HAVE_VAE_WEIGHTS
    v.push_back(make("vae", &nn::vae::kEncoderModel, nn::vae::kKlOrder, nn::vae::kKlPerLatent,
                     nn::vae::kInputsSha256));
#endif
    return v;
  }();
  return reps;
}

}  // namespace

const Representation* find_representation(const std::string& name) {
  for (const auto& r : all())
    if (r.name == name) return &r;
  return nullptr;
}

std::vector<int> ball_latents(const std::string& name) {
  const std::string path =
      std::string(CURIO_MODELS_DIR) + "/" + name + ".factor_report.json";
  std::ifstream f(path);
  if (!f) return {};
  std::vector<int> latents;
  try {
    const auto report = nlohmann::json::parse(f);
    const auto& list = report.at("latents");
    for (size_t i = 0; i < list.size(); ++i) {
      const auto& l = list[i];
      const std::string factor = l.value("best_factor", "");
      const int index = l.contains("index") ? l["index"].get<int>() : static_cast<int>(i);
      if (l.value("active", false) && factor.rfind("ball", 0) == 0 &&
          l.value("abs_corr_best", 0.0) >= 0.5)
        latents.push_back(index);
    }
  } catch (const std::exception&) {
    return {};
  }
  std::sort(latents.begin(), latents.end());
  return latents;
}

std::vector<std::string> available_representations() {
  std::vector<std::string> names;
  for (const auto& r : all()) names.push_back(r.name);
  return names;
}

}  // namespace curio::lab
