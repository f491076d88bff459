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

// Reads and validates both files, renders the calibration images, calibrates, quantizes.
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
// compares it, and the content hash, with the header's banner.
CheckResult check_header(const std::string& header_path, const std::string& model_path,
                         const std::string& meta_path);

}  // namespace curio::quantize
