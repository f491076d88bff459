#include "host_tools/quantize/pipeline.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "host_tools/model_io/float_encoder.hpp"

namespace curio::quantize {

std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(tmp + ": cannot create");
    out << text;
    out.close();
    if (!out) throw std::runtime_error(tmp + ": write failed");
  }
  std::filesystem::rename(tmp, path);
}

std::string model_name_from_path(const std::string& model_path) {
  return std::filesystem::path(model_path).stem().string();
}

std::string header_path_for(const std::string& model_path, const std::string& name) {
  return (std::filesystem::path(model_path).parent_path() / (name + "_weights.hpp")).string();
}

QuantizedFiles quantize_files(const std::string& model_path, const std::string& meta_path,
                              const CalibrationSettings& calibration, const Progress& progress) {
  QuantizedFiles q;
  const std::string model_bytes = read_file_bytes(model_path);
  const std::string meta_bytes = read_file_bytes(meta_path);
  q.model = model_io::parse_float_model(model_bytes, model_path);
  q.meta = model_io::parse_model_meta(meta_bytes, meta_path);
  q.inputs_sha256 = inputs_fingerprint(model_bytes, meta_bytes, calibration);
  const model_io::FloatEncoder float_encoder(q.model);

  progress("rendering " + std::to_string(calibration.images) + " calibration images (seed " +
           std::to_string(calibration.seed) + ")");
  const auto images = render_scenes(calibration.images, calibration.seed);
  std::vector<CameraFrame> frames;
  frames.reserve(images.size());
  for (const auto& image : images) frames.push_back(to_camera_frame(image.data()));
  progress("calibrating activation ranges");
  const ActivationRanges ranges = calibrate(float_encoder, frames);
  for (int t = 0; t < kCalibratedTensors; ++t) {
    char line[160];
    std::snprintf(line, sizeof line, "  %-6s range [%.4g, %.4g]",
                  kCalibratedTensorNames[static_cast<size_t>(t)], ranges.tensor_min(t),
                  ranges.tensor_max(t));
    progress(line);
  }
  q.encoder = quantize_encoder(q.model, ranges, calibration.scales);
  const double corrected = correct_latent_bias(float_encoder, frames, &q.encoder);
  char line[120];
  std::snprintf(line, sizeof line, "latent bias correction: largest mean shift %.5f", corrected);
  progress(line);
  return q;
}

CheckResult check_header(const std::string& header_path, const std::string& model_path,
                         const std::string& meta_path) {
  CheckResult r;
  const HeaderBanner banner = parse_header_banner(read_file_bytes(header_path));
  const std::string regenerate = "regenerate it with:\n  " + banner.command;
  if (banner.actual_content_sha256 != banner.content_sha256) {
    r.message = header_path + " was edited by hand (content hash differs); " + regenerate;
    return r;
  }
  if (banner.quantizer != kQuantizerVersion) {
    r.message = header_path + " was made by '" + banner.quantizer + "', this is '" +
                kQuantizerVersion + "'; " + regenerate;
    return r;
  }
  const CalibrationSettings calibration = parse_calibration(banner.calibration);
  const std::string now =
      inputs_fingerprint(read_file_bytes(model_path), read_file_bytes(meta_path), calibration);
  if (now != banner.inputs_sha256) {
    r.message = header_path + " is stale: " + model_path + " or " + meta_path +
                " changed since it was generated; " + regenerate;
    return r;
  }
  r.up_to_date = true;
  r.message = header_path + " is up to date";
  return r;
}

}  // namespace curio::quantize
