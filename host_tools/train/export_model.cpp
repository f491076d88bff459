#include "host_tools/train/export_model.hpp"

#include <filesystem>
#include <stdexcept>

#include "host_tools/model_io/encoder_spec.hpp"
#include "host_tools/model_io/float_model.hpp"
#include "host_tools/model_io/model_meta.hpp"
#include "host_tools/vae/evaluate.hpp"
#include "host_tools/vae/scene_set.hpp"

namespace curio::train {

ExportResult export_model(Vae& model, const Recipe& recipe, int64_t iteration,
                          const std::string& dir, const std::string& name, int64_t kl_images,
                          const std::string& made_by) {
  namespace mio = curio::model_io;
  std::filesystem::create_directories(dir);
  ExportResult result;
  result.model_path = (std::filesystem::path(dir) / (name + ".cfm")).string();
  result.meta_path = mio::meta_path_for(result.model_path);

  // Encoder tensors in the file order the firmware tools expect, then the decoder.
  const auto params = model->named_parameters();
  std::vector<mio::FloatTensor> tensors;
  auto add = [&](const std::string& key) {
    const auto t = params[key].detach().to(torch::kFloat32).contiguous();
    mio::FloatTensor ft{key, t.sizes().vec(), {}};
    ft.data.assign(t.data_ptr<float>(), t.data_ptr<float>() + t.numel());
    tensors.push_back(std::move(ft));
  };
  for (const auto& spec : mio::encoder_tensor_specs()) {
    if (!params.contains(spec.name)) throw std::runtime_error("model lacks " + spec.name);
    add(spec.name);
  }
  for (const auto& p : params)
    if (p.key().starts_with("dec.")) add(p.key());
  mio::write_float_model(result.model_path, tensors);

  const SceneSet scenes = render_scene_set(kl_images, recipe.seed, kKlStream, 1);
  const Encoded e = encode_all(model, scenes.images);
  result.kl_per_latent = mean_kl(e);

  mio::ModelMeta meta;
  meta.model = recipe.model;
  for (size_t l = 0; l < meta.kl_per_latent.size(); ++l)
    meta.kl_per_latent[l] = result.kl_per_latent.at(l);
  meta.kl_order = mio::kl_order_of(meta.kl_per_latent);
  meta.json = {{"recipe", to_json(recipe)},
               {"iteration", iteration},
               {"kl_images", kl_images},
               {"kl_note", "mean KL(q(z|x) || N(0,1)) per latent over kl_images scenes with ball "
                           "and distractor uniform in [-1,1]^2 (SPEC 2.4), nats"},
               {"trainer", "curio-train (LibTorch " TORCH_VERSION ")"}};
  if (!made_by.empty()) meta.json["made_by"] = made_by;
  mio::write_model_meta(result.meta_path, meta);
  return result;
}

}  // namespace curio::train
