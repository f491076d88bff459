#include "host_tools/model_io/model_meta.hpp"

#include <algorithm>
#include <fstream>
#include <numeric>
#include <sstream>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/bounded_read.hpp"

#include "host_tools/model_io/float_model.hpp"

namespace curio::model_io {

std::array<int, kLatents> kl_order_of(const std::array<double, kLatents>& kl) {
  std::array<int, kLatents> order{};
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return kl[static_cast<size_t>(a)] > kl[static_cast<size_t>(b)];
  });
  return order;
}

std::string meta_path_for(const std::string& model_path) {
  const auto slash = model_path.find_last_of('/');
  const auto dot = model_path.find_last_of('.');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_ext ? model_path.substr(0, dot) : model_path) + ".meta.json";
}

ModelMeta parse_model_meta(const std::string& text, const std::string& origin) {
  ModelMeta meta;
  try {
    meta.json = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw ModelFormatError(origin + ": not valid JSON: " + e.what());
  }
  const auto& j = meta.json;
  auto fail = [&](const std::string& why) { throw ModelFormatError(origin + ": " + why); };
  if (!j.is_object()) fail("top level must be a JSON object");
  if (!j.contains("model") || !j["model"].is_string()) fail("missing string key \"model\"");
  meta.model = j["model"].get<std::string>();
  if (meta.model != "beta-vae" && meta.model != "vae") {
    fail("\"model\" is \"" + meta.model + "\", expected \"beta-vae\" or \"vae\"");
  }
  if (!j.contains("kl_per_latent") || !j["kl_per_latent"].is_array() ||
      j["kl_per_latent"].size() != kLatents) {
    fail("\"kl_per_latent\" must be an array of " + std::to_string(kLatents) + " numbers");
  }
  for (size_t i = 0; i < kLatents; ++i) {
    if (!j["kl_per_latent"][i].is_number())
      fail("\"kl_per_latent\"[" + std::to_string(i) + "] is not a number");
    meta.kl_per_latent[i] = j["kl_per_latent"][i].get<double>();
  }
  if (!j.contains("kl_order") || !j["kl_order"].is_array() || j["kl_order"].size() != kLatents) {
    fail("\"kl_order\" must be an array of " + std::to_string(kLatents) + " latent indices");
  }
  std::array<bool, kLatents> used{};
  for (size_t i = 0; i < kLatents; ++i) {
    const auto& v = j["kl_order"][i];
    if (!v.is_number_integer()) fail("\"kl_order\"[" + std::to_string(i) + "] is not an integer");
    const int idx = v.get<int>();
    if (idx < 0 || idx >= kLatents || used[static_cast<size_t>(idx)]) {
      fail("\"kl_order\" must be a permutation of 0.." + std::to_string(kLatents - 1));
    }
    used[static_cast<size_t>(idx)] = true;
    meta.kl_order[i] = idx;
  }
  for (size_t i = 0; i + 1 < kLatents; ++i) {
    const auto a = static_cast<size_t>(meta.kl_order[i]);
    const auto b = static_cast<size_t>(meta.kl_order[i + 1]);
    if (meta.kl_per_latent[a] < meta.kl_per_latent[b]) {
      fail("\"kl_order\" is not sorted by decreasing \"kl_per_latent\" (latent " +
           std::to_string(a) + " before latent " + std::to_string(b) + ")");
    }
  }
  return meta;
}

ModelMeta read_model_meta(const std::string& path) {
  std::string bytes, error;
  if (!host::read_file_bounded(path, host::kJsonFileLimit, &bytes, &error, "model meta JSON"))
    throw ModelFormatError(error);
  return parse_model_meta(bytes, path);
}

void write_model_meta(const std::string& path, const ModelMeta& meta) {
  nlohmann::json j = meta.json.is_object() ? meta.json : nlohmann::json::object();
  j["model"] = meta.model;
  j["kl_per_latent"] = meta.kl_per_latent;
  j["kl_order"] = meta.kl_order;
  std::string error;  // atomically, as the model file
  if (!host::write_file_atomically(path, j.dump(2) + "\n", &error))
    throw ModelFormatError("cannot write the model meta JSON: " + error);
}

}  // namespace curio::model_io
