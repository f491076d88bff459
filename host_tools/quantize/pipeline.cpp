#include "host_tools/quantize/pipeline.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/bounded_read.hpp"
#include "host_tools/model_io/float_encoder.hpp"
#include "host_tools/quantize/calibration.hpp"
#include "host_tools/quantize/sha256.hpp"

namespace curio::quantize {

std::string read_file_bytes(const std::string& path) {
  // The largest of curio-quantize's inputs is a float model (~1.5 MiB) or a weights header.
  return host::read_file_bounded_or_throw(path, host::kModelFileLimit, "model input");
}

void write_file_atomically(const std::string& path, const std::string& text) {
  // A temporary file beside it, fsync'ed and renamed over it; a link, FIFO, device or
  // directory at `path` is refused, never written through.
  host::write_file_atomically_or_throw(path, text);
}

std::string model_name_from_path(const std::string& model_path) {
  return std::filesystem::path(model_path).stem().string();
}

std::string header_path_for(const std::string& model_path, const std::string& name) {
  return (std::filesystem::path(model_path).parent_path() / (name + "_weights.hpp")).string();
}

void check_meta_belongs_to_model(const std::string& model_bytes, const model_io::FloatModel& model,
                                 const model_io::ModelMeta& meta, const std::string& model_path,
                                 const std::string& meta_path) {
  const std::string another = meta_path + " is not the meta JSON of " + model_path + ": ";
  if (meta.json.contains("model_sha256")) {
    const auto& h = meta.json["model_sha256"];
    const std::string actual = sha256_hex(model_bytes);
    if (!h.is_string() || h.get<std::string>() != actual)
      throw std::runtime_error(another + "its \"model_sha256\" is " + h.dump() + ", the model's " +
                               actual + " (pass the meta written with this model)");
    return;
  }
  // The model's own KL(q(z|x) || N(0,1)) per latent, as the trainer measured it for the meta.
  const model_io::FloatEncoder encoder(model);
  const auto images = render_scenes(kMetaCheckScenes, /*seed=*/0x6d657461);
  std::array<double, model_io::kLatents> kl{};
  model_io::EncoderTrace trace;
  for (const auto& image : images) {
    encoder.forward(image.data(), &trace);
    for (int j = 0; j < model_io::kLatents; ++j) {
      const double mu = trace.out[static_cast<size_t>(j)];
      const double lv = trace.out[static_cast<size_t>(j + model_io::kLatents)];
      kl[static_cast<size_t>(j)] += 0.5 * (mu * mu + std::exp(lv) - lv - 1.0);
    }
  }
  for (int j = 0; j < model_io::kLatents; ++j) {
    const double model_kl = kl[static_cast<size_t>(j)] / static_cast<double>(images.size());
    const double meta_kl = meta.kl_per_latent[static_cast<size_t>(j)];
    if (std::abs(model_kl - meta_kl) > 0.35 + 0.25 * meta_kl) {
      char line[200];
      std::snprintf(line, sizeof line,
                    "latent %d has KL %.3f nats in the meta but %.3f in the model (over %d "
                    "rendered scenes)",
                    j, meta_kl, model_kl, kMetaCheckScenes);
      throw std::runtime_error(another + line + "; pass the meta written with this model");
    }
  }
}

QuantizedFiles quantize_files(const std::string& model_path, const std::string& meta_path,
                              const CalibrationSettings& calibration, const Progress& progress) {
  QuantizedFiles q;
  const std::string model_bytes = read_file_bytes(model_path);
  const std::string meta_bytes = read_file_bytes(meta_path);
  q.model = model_io::parse_float_model(model_bytes, model_path);
  q.meta = model_io::parse_model_meta(meta_bytes, meta_path);
  progress("checking that " + meta_path + " belongs to " + model_path);
  check_meta_belongs_to_model(model_bytes, q.model, q.meta, model_path, meta_path);
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
  const std::string model_bytes = read_file_bytes(model_path);
  const std::string meta_bytes = read_file_bytes(meta_path);
  try {
    check_meta_belongs_to_model(model_bytes, model_io::parse_float_model(model_bytes, model_path),
                                model_io::parse_model_meta(meta_bytes, meta_path), model_path,
                                meta_path);
  } catch (const std::runtime_error& e) {
    r.message = e.what();
    return r;
  }
  const std::string now = inputs_fingerprint(model_bytes, meta_bytes, calibration);
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
