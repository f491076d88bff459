// The JSON sidecar `<name>.meta.json` the trainer writes beside a float model file.
// Required keys: "model" ("beta-vae" | "vae"), "kl_per_latent" (10 numbers, nats, SPEC §2.4)
// and "kl_order" (latent indices by decreasing KL). Other keys are kept as-is in `json`.
#pragma once
#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "host_tools/model_io/encoder_spec.hpp"

namespace curio::model_io {

struct ModelMeta {
  std::string model;  // "beta-vae" or "vae"
  std::array<double, kLatents> kl_per_latent{};
  std::array<int, kLatents> kl_order{};  // kl_order[0] = latent with the largest KL
  nlohmann::json json;                   // the whole document (extra keys included)
};

// Throws ModelFormatError (float_model.hpp) naming the file and the key at fault: missing
// file, bad JSON, missing key, wrong length, kl_order not a permutation of 0..9 or not
// sorted by decreasing kl_per_latent.
ModelMeta read_model_meta(const std::string& path);
ModelMeta parse_model_meta(const std::string& text, const std::string& origin);

// Writes `meta.json` with the three required keys set from the fields (pretty-printed).
void write_model_meta(const std::string& path, const ModelMeta& meta);

// Latent indices sorted by decreasing KL; ties keep the lower index first.
std::array<int, kLatents> kl_order_of(const std::array<double, kLatents>& kl_per_latent);

// "<dir>/<stem>.meta.json" for "<dir>/<stem>.cfm".
std::string meta_path_for(const std::string& model_path);

}  // namespace curio::model_io
