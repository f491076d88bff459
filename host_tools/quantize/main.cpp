// curio-quantize: float encoder (CURIOFM1 + meta JSON) → int8 weights header for the
// firmware; checks committed headers; measures the int8-vs-float error. Exit codes as every
// Curio program (host_tools/cli/command_line.hpp): 2 for a usage error, 1 for a failure or a stale
// header, 77 from check-dir when there is nothing to check.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "host_tools/cli/command_line.hpp"
#include "host_tools/model_io/float_encoder.hpp"
#include "host_tools/model_io/model_meta.hpp"
#include "host_tools/quantize/evaluation.hpp"
#include "host_tools/quantize/pipeline.hpp"

namespace {

namespace fs = std::filesystem;
using namespace curio::quantize;

constexpr int kSkipExitCode = 77;  // ctest SKIP_RETURN_CODE

void progress(const std::string& line) {
  std::fprintf(stderr, "curio-quantize: %s\n", line.c_str());
}

std::string shell_quote(const std::string& s) {
  if (s.find_first_of(" \t'\"$\\") == std::string::npos) return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct Options {
  std::string model, meta, name, header, dir;  // header: quantize's output, check's input
  CalibrationSettings calibration;
  int test_images = 1000;
  uint64_t test_seed = 2;
};

std::string meta_or_default(const Options& o) {
  return o.meta.empty() ? curio::model_io::meta_path_for(o.model) : o.meta;
}

int run_quantize(const Options& o) {
  const std::string meta = meta_or_default(o);
  const std::string& name = o.name;  // set and checked by main()
  const std::string out = o.header.empty() ? header_path_for(o.model, name) : o.header;
  QuantizedFiles q = quantize_files(o.model, meta, o.calibration, progress);
  HeaderSource src;
  src.name = name;
  src.calibration = o.calibration;
  src.inputs_sha256 = q.inputs_sha256;
  src.command = "curio-quantize quantize --model " + shell_quote(o.model) + " --meta " +
                shell_quote(meta) + " --name " + name + " --header " + shell_quote(out) +
                " --images " + std::to_string(o.calibration.images) + " --seed " +
                std::to_string(o.calibration.seed) + " --activations " +
                to_string(o.calibration.scales);
  write_file_atomically(out, emit_header(src, q.encoder, q.meta));
  progress("wrote " + out + " (namespace curio::nn::" + name + ")");
  return 0;
}

int run_check(const Options& o) {
  const CheckResult r = check_header(o.header, o.model, meta_or_default(o));
  (r.up_to_date ? std::cout : std::cerr) << r.message << "\n";
  return r.up_to_date ? 0 : 1;
}

int run_check_dir(const Options& o) {
  int models = 0;
  int stale = 0;
  for (const auto& entry : fs::directory_iterator(o.dir)) {
    if (entry.path().extension() != ".cfm") continue;
    ++models;
    const std::string model = entry.path().string();
    const std::string header = header_path_for(model, model_name_from_path(model));
    if (!fs::exists(header)) {
      std::cerr << model << " has no header " << header
                << "; generate it with:\n  curio-quantize quantize --model " << model << "\n";
      ++stale;
      continue;
    }
    const CheckResult r = check_header(header, model, curio::model_io::meta_path_for(model));
    (r.up_to_date ? std::cout : std::cerr) << r.message << "\n";
    stale += r.up_to_date ? 0 : 1;
  }
  if (models == 0) {
    std::cout << "no float models (*.cfm) in " << o.dir << ": nothing to check (skipped)\n";
    return kSkipExitCode;
  }
  return stale == 0 ? 0 : 1;
}

int run_evaluate(const Options& o) {
  QuantizedFiles q = quantize_files(o.model, meta_or_default(o), o.calibration, progress);
  const curio::model_io::FloatEncoder float_encoder(q.model);
  progress("rendering " + std::to_string(o.test_images) + " test images (seed " +
           std::to_string(o.test_seed) + ")");
  const auto images = render_scenes(o.test_images, o.test_seed);
  const Int8VsFloat r = compare_int8_to_float(float_encoder, q.encoder.model(), images);
  std::printf("images %d  max|dmu| %.5f  mean|dmu| %.6f  faults %d\n", r.images, r.max_abs_mu_error,
              r.mean_abs_mu_error, r.encoder_faults);
  std::printf("latent  max|dmu|   KL float  KL int8\n");
  for (size_t j = 0; j < curio::nn::kLatents; ++j) {
    std::printf("%6zu  %8.5f  %8.4f  %8.4f\n", j, r.max_abs_mu_error_per_latent[j], r.kl_float[j],
                r.kl_int8[j]);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"curio-quantize: int8 quantizer and weights-header emitter for the Curio encoder",
               "curio-quantize"};
  app.require_subcommand(1);
  Options o;
  constexpr int kMaxImages = 1'000'000;

  auto add_calibration = [&](CLI::App* sub) {
    sub->add_option("--images", o.calibration.images, "calibration images to render")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxImages));
    sub->add_option("--seed", o.calibration.seed, "seed of the calibration scenes")
        ->capture_default_str()
        ->check(curio::cli::kSeed);
    sub->add_option_function<std::string>(
           "--activations",
           [&](const std::string& v) {
             if (!parse_activation_scales(v, &o.calibration.scales)) {
               throw CLI::ValidationError("--activations", "per-tensor or per-channel");
             }
           },
           "activation scales: per-tensor (default, TFLite) or per-channel")
        ->check(CLI::IsMember({"per-tensor", "per-channel"}));
  };
  const auto add_meta = [&](CLI::App* sub) {
    sub->add_option("--meta", o.meta,
                    "meta JSON (default: <model stem>.meta.json); refused if it is another "
                    "model's: its \"model_sha256\" must be the model file's, or, without one, "
                    "its KL per latent the model's own (within 0.35 nats + 25 %, over 128 "
                    "rendered scenes)")
        ->check(CLI::ExistingFile);
  };

  auto* quantize = app.add_subcommand("quantize", "quantize a float model into a weights header");
  quantize->add_option("--model", o.model, "float model file (CURIOFM1, .cfm)")
      ->required()
      ->check(CLI::ExistingFile);
  add_meta(quantize);
  quantize->add_option("--name", o.name, "C++ namespace curio::nn::<name> (default: model stem)");
  quantize->add_option("--header", o.header,
                        "header file to write (default: <model dir>/<name>_weights.hpp)")
      ->check(curio::cli::kOutputFile);
  add_calibration(quantize);

  auto* check = app.add_subcommand("check", "fail if a weights header is stale or edited");
  check->add_option("--header", o.header, "generated header")->required()->check(CLI::ExistingFile);
  check->add_option("--model", o.model, "float model file it came from")
      ->required()
      ->check(CLI::ExistingFile);
  add_meta(check);

  auto* check_dir = app.add_subcommand(
      "check-dir", "check every <name>.cfm in a folder against <name>_weights.hpp (exit 77: none)");
  check_dir->add_option("dir", o.dir, "folder, e.g. firmware/nn/models")
      ->required()
      ->check(CLI::ExistingDirectory);

  auto* evaluate =
      app.add_subcommand("evaluate", "quantize in memory and report int8 vs float μ error");
  evaluate->add_option("--model", o.model, "float model file")
      ->required()
      ->check(CLI::ExistingFile);
  add_meta(evaluate);
  evaluate->add_option("--test-images", o.test_images, "rendered test images")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxImages));
  evaluate->add_option("--test-seed", o.test_seed, "seed of the test scenes")
      ->capture_default_str()
      ->check(curio::cli::kSeed);
  add_calibration(evaluate);

  if (const auto code = curio::cli::parse(app, argc, argv)) return *code;
  if (quantize->parsed()) {
    const bool stem = o.name.empty();
    if (stem) o.name = model_name_from_path(o.model);
    if (!is_identifier(o.name)) {
      return curio::cli::usage_error(
          *quantize, stem ? "--model's stem '" + o.name + "' is not a C++ identifier: pass --name"
                          : "--name '" + o.name + "' is not a C++ identifier");
    }
  }
  try {
    if (quantize->parsed()) return run_quantize(o);
    if (check->parsed()) return run_check(o);
    if (check_dir->parsed()) return run_check_dir(o);
    if (evaluate->parsed()) return run_evaluate(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "curio-quantize: error: %s\n", e.what());
    return curio::cli::kRuntimeFailure;
  }
  return curio::cli::kRuntimeFailure;
}
