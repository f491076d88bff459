#include "tests/nn/synthetic_model.hpp"

#include <cmath>
#include <filesystem>

#include "firmware/explore/prng.hpp"
#include "host_tools/model_io/encoder_spec.hpp"
#include "host_tools/quantize/sha256.hpp"

namespace curio::nn::testing {

std::vector<model_io::FloatTensor> synthetic_encoder_tensors(uint64_t seed) {
  Prng rng(seed);
  std::vector<model_io::FloatTensor> tensors;
  for (const auto& spec : model_io::encoder_tensor_specs()) {
    model_io::FloatTensor t{spec.name, spec.dims, {}};
    t.data.resize(static_cast<size_t>(t.element_count()));
    const bool is_bias = spec.dims.size() == 1;
    int64_t fan_in = 1;
    for (size_t d = 1; d < spec.dims.size(); ++d) fan_in *= spec.dims[d];
    const double std = is_bias ? 0.05 : std::sqrt(2.0 / static_cast<double>(fan_in));
    for (auto& v : t.data) v = static_cast<float>(std * rng.normal());
    tensors.push_back(std::move(t));
  }
  // A decoder tensor the quantizer must ignore.
  tensors.push_back({"dec.fc0.weight", {2, 2}, {1, 2, 3, 4}});
  return tensors;
}

model_io::ModelMeta synthetic_meta(uint64_t seed) {
  Prng rng(seed ^ 0x9e3779b97f4a7c15ULL);
  model_io::ModelMeta meta;
  meta.model = "vae";
  for (auto& kl : meta.kl_per_latent) kl = rng.uniform(0.0, 3.0);
  meta.kl_order = model_io::kl_order_of(meta.kl_per_latent);
  meta.json = {{"synthetic", true}, {"seed", seed}};
  return meta;
}

std::string write_synthetic_model(const std::string& dir, const std::string& name, uint64_t seed) {
  std::filesystem::create_directories(dir);
  const std::string path = (std::filesystem::path(dir) / (name + ".cfm")).string();
  const auto tensors = synthetic_encoder_tensors(seed);
  model_io::write_float_model(path, tensors);
  // Its KL per latent is made up, so the meta names its model by hash (curio-quantize checks
  // that a meta belongs to its model: check_meta_belongs_to_model).
  model_io::ModelMeta meta = synthetic_meta(seed);
  meta.json["model_sha256"] = quantize::sha256_hex(model_io::serialize_float_model(tensors));
  model_io::write_model_meta(model_io::meta_path_for(path), meta);
  return path;
}

}  // namespace curio::nn::testing
