// Writes a quantized encoder as a C++ header for the firmware
// (firmware/nn/models/<name>_weights.hpp, namespace curio::nn::<name>) and reads back its
// banner so `curio-quantize check` can tell a stale or hand-edited header.
#pragma once
#include <cstdint>
#include <string>

#include "host_tools/model_io/model_meta.hpp"
#include "host_tools/quantize/encoder_quantizer.hpp"

namespace curio::quantize {

struct CalibrationSettings {
  int images = 1000;
  uint64_t seed = 1;
  ActivationScales scales = ActivationScales::kPerTensor;
  std::string describe() const;  // "images=1000 seed=1 activations=per-tensor"
};

// SHA-256 over the float model file's bytes, the meta JSON's bytes, the quantizer
// version and the calibration settings: what the header is a function of.
std::string inputs_fingerprint(const std::string& model_bytes, const std::string& meta_bytes,
                               const CalibrationSettings& calibration);

struct HeaderSource {
  std::string name;     // C++ identifier: namespace curio::nn::<name>
  std::string command;  // the command line that regenerates the header
  std::string inputs_sha256;
  CalibrationSettings calibration;
};

std::string emit_header(const HeaderSource& source, const QuantizedEncoder& encoder,
                        const model_io::ModelMeta& meta);

struct HeaderBanner {
  std::string command;
  std::string quantizer;
  std::string calibration;
  std::string inputs_sha256;
  std::string content_sha256;         // as recorded
  std::string actual_content_sha256;  // of the text after the banner, as found
};

// Throws std::runtime_error when the text has no complete banner.
HeaderBanner parse_header_banner(const std::string& text);

// Parses describe()'s text back (throws on anything else).
CalibrationSettings parse_calibration(const std::string& text);

bool is_identifier(const std::string& name);

}  // namespace curio::quantize
