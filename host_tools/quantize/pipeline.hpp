// The quantizer's jobs over files, shared by the CLI and the tests: quantize a float model
// file (+ meta JSON) into a header, and check a committed header against its inputs.
#pragma once
#include <functional>
#include <string>

#include "host_tools/model_io/float_model.hpp"
#include "host_tools/model_io/model_meta.hpp"
#include "host_tools/quantize/encoder_quantizer.hpp"
#include "host_tools/quantize/header_emitter.hpp"

namespace curio::quantize {

using Progress = std::function<void(const std::string&)>;

struct QuantizedFiles {
  model_io::FloatModel model;
  model_io::ModelMeta meta;
  QuantizedEncoder encoder;
  std::string inputs_sha256;
};

std::string read_file_bytes(const std::string& path);  // throws std::runtime_error
// Writes via a temporary file and rename, so a failed run leaves no half header.
void write_file_atomically(const std::string& path, const std::string& text);

// Whether the meta JSON belongs to the model, so that no header carries another model's KL
// order: a meta with "model_sha256" (the SHA-256 of the model file) must name this model's;
// one without it must agree with the model's own KL per latent, measured over
// kMetaCheckScenes rendered scenes (each latent within 0.35 nats + 25 % of the meta's value).
// Throws std::runtime_error naming both files and the first latent that disagrees.
inline constexpr int kMetaCheckScenes = 128;
void check_meta_belongs_to_model(const std::string& model_bytes, const model_io::FloatModel& model,
                                 const model_io::ModelMeta& meta, const std::string& model_path,
                                 const std::string& meta_path);

// Reads and validates both files (check_meta_belongs_to_model included), renders the
// calibration images, calibrates, quantizes.
QuantizedFiles quantize_files(const std::string& model_path, const std::string& meta_path,
                              const CalibrationSettings& calibration, const Progress& progress);

// "<stem>" of ".../<stem>.cfm".
std::string model_name_from_path(const std::string& model_path);
// "<dir>/<name>_weights.hpp" beside the model file.
std::string header_path_for(const std::string& model_path, const std::string& name);

struct CheckResult {
  bool up_to_date = false;
  std::string message;  // what is wrong and how to fix it, or "up to date"
};

// Recomputes the inputs' fingerprint with the header's own calibration settings and
// compares it, and the content hash, with the header's banner; a meta that does not belong to
// the model is refused first (check_meta_belongs_to_model).
CheckResult check_header(const std::string& header_path, const std::string& model_path,
                         const std::string& meta_path);

}  // namespace curio::quantize
