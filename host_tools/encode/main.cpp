// curio-encode: a user's images in, what the goal space makes of them out. PNG files or
// folders of them (64×64 8-bit RGB, as the arm's camera gives; other sizes with --resize);
// for each image μ and log σ² of every latent from the int8 encoder the controller runs, and
// from the float model beside its weights with the difference; the latents ranked by KL and
// grouped into goal modules as MGE groups them; latents.csv, summary.json and figure.png in
// --out. An image that cannot be read gets one line naming it, and the others are still
// encoded and written. Exit codes (host_tools/cli/command_line.hpp): 0 every image encoded, 1 some
// image refused or nothing written, 2 a usage error.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "host_tools/cli/command_line.hpp"
#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/output_folder.hpp"
#include "host_tools/encode/encode_images.hpp"
#include "sim/render.hpp"

namespace {

namespace fs = std::filesystem;
using namespace curio::encode;

// The PNG files the inputs name: files as given, a folder's *.png (any case) sorted by name.
// Inputs that name nothing usable go to *refused.
std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs,
                                       std::vector<std::pair<std::string, std::string>>* refused) {
  std::vector<std::string> files;
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(in, ec)) {
        std::string ext = e.path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
        if (e.is_regular_file() && ext == ".png") found.push_back(e.path().string());
      }
      if (ec) refused->emplace_back(in, in + ": cannot list the folder (" + ec.message() + ")");
      else if (found.empty()) refused->emplace_back(in, in + ": folder has no .png files");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::exists(in, ec)) {
      files.push_back(in);
    } else {
      refused->emplace_back(in, in + ": no such file or folder");
    }
  }
  return files;
}

std::string signed2(float v) {
  return fmt::format("{:+.2f}", v);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "curio-encode: what a goal space makes of your images. Each PNG (64x64 8-bit RGB, as the "
      "arm's camera gives) goes through the int8 encoder the controller runs, and through the "
      "float model it was quantized from; the latents are ranked by KL and grouped into goal "
      "modules as MGE groups them. Writes <out>/latents.csv (one row per image and latent), "
      "<out>/summary.json and <out>/figure.png (per image: the image, its reconstruction, then "
      "7 decodings from -3 to 3 of each latent of its two most active modules).",
      "curio-encode"};
  std::vector<std::string> inputs;
  std::string weights = "beta_vae";
  std::string out = "encode_out";
  bool resize = false;
  int figure_images = 8;
  bool quiet = false;
  int threads = 1;
  app.add_option("inputs", inputs, "PNG files, or folders whose .png files are encoded (sorted by name)")
      ->required();
  app.add_option("--weights", weights,
                 "Goal space: the int8 weights compiled into this build (beta_vae, vae)")
      ->capture_default_str();
  app.add_option("--out", out, "Output folder (created; latents.csv, summary.json, figure.png)")
      ->check(curio::cli::kOutputFolder)
      ->capture_default_str();
  app.add_flag("--resize", resize,
               "Resample images of another size to 64x64: per axis an area average (box filter) when "
               "shrinking, linear between pixel centres when enlarging (otherwise they are refused)");
  app.add_option("--figure-images", figure_images, "Images shown in figure.png (the first ones)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app.add_option("--threads", threads, "Threads for the int8 encoder (the codes do not depend on it)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_flag("--quiet", quiet, "No line per image");
  if (const auto code = curio::cli::parse(app, argc, argv)) return *code;

  std::unique_ptr<GoalSpace> space;
  try {
    space = std::make_unique<GoalSpace>(weights, CURIO_MODELS_DIR);
  } catch (const std::exception& e) {
    return curio::cli::usage_error(app, e.what());
  }

  std::vector<std::pair<std::string, std::string>> refused;
  const std::vector<std::string> files = expand_inputs(inputs, &refused);
  std::string error;
  const auto claim = curio::host::claim_output_folder_or_say("curio-encode", out, curio::host::OutputAccess::kExclusive);
  if (!claim) return curio::cli::kRuntimeFailure;
  if (!space->float_note().empty())
    std::fprintf(stderr, "curio-encode: %s (int8 codes only, no figure)\n", space->float_note().c_str());

  if (!quiet)
    std::printf("per image, each goal module m<k>[its latents' int8 mu] and its KL from the prior "
                "(nats; the most active modules are traversed in figure.png)\n");
  std::vector<CameraImage> images;
  for (const std::string& f : files) {
    CameraImage image;
    const std::string why = read_camera_png(f, resize, &image);
    if (!why.empty()) {
      std::fprintf(stderr, "curio-encode: %s\n", why.c_str());
      refused.emplace_back(f, why);
      continue;
    }
    images.push_back(image);
  }
  std::vector<ImageCodes> codes;
  try {
    codes = space->encode_all(images, threads);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "curio-encode: %s\n", e.what());
    return curio::cli::kRuntimeFailure;
  }
  for (const ImageCodes& c : codes) {
    if (quiet) break;
    std::string line = fmt::format("{}{}:", c.image.path,
                                   c.image.resized ? fmt::format(" ({}x{} resized)", c.image.source_width, c.image.source_height) : "");
    for (size_t m = 0; m < space->modules().size(); ++m) {
      line += fmt::format(" m{}[", m);
      for (size_t k = 0; k < space->modules()[m].size(); ++k) {
        const int l = space->modules()[m][k];
        line += fmt::format("{}z{} {}", k ? " " : "", l, signed2(c.mu_int8[static_cast<size_t>(l)]));
      }
      line += fmt::format("] {:.1f}", c.module_activity[m]);
    }
    if (c.has_float) {
      float worst = 0.0f;
      for (size_t l = 0; l < static_cast<size_t>(kLatents); ++l) worst = std::max(worst, std::abs(c.mu_int8[l] - c.mu_float[l]));
      line += fmt::format("  (int8 vs float: max |dmu| {:.3f})", worst);
    }
    std::printf("%s\n", line.c_str());
  }
  for (const auto& [file, why] : refused)
    if (std::find(files.begin(), files.end(), file) == files.end()) std::fprintf(stderr, "curio-encode: %s\n", why.c_str());

  try {
    curio::host::write_file_atomically_or_throw((fs::path(out) / "latents.csv").string(), codes_csv(*space, codes));
    curio::host::write_file_atomically_or_throw((fs::path(out) / "summary.json").string(),
                                                codes_json(*space, codes, refused).dump(2) + "\n");
    if (space->has_decoder() && !codes.empty()) {
      const Figure fig = codes_figure(*space, codes, figure_images);
      if (!curio::sim::write_png((fs::path(out) / "figure.png").string(), fig.hwc.data(), fig.width, fig.height, &error))
        throw std::runtime_error(error);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "curio-encode: %s\n", e.what());
    return curio::cli::kRuntimeFailure;
  }
  std::printf("%zu image(s) encoded with %s (modules m0..m%zu as MGE groups the latents: ", codes.size(),
              weights.c_str(), space->modules().size() - 1);
  for (size_t m = 0; m < space->modules().size(); ++m) {
    std::printf("%sm%zu=", m ? ", " : "", m);
    for (size_t k = 0; k < space->modules()[m].size(); ++k) std::printf("%sz%d", k ? "+" : "", space->modules()[m][k]);
  }
  std::printf("), %zu refused; results in %s\n", refused.size(), out.c_str());
  return refused.empty() && !codes.empty() ? 0 : curio::cli::kRuntimeFailure;
}
