#include "sim/cli/render_command.hpp"

#include <cmath>
#include <vector>

#include "sim/render.hpp"

namespace curio::sim {

CLI::App* add_render_command(CLI::App* app, RenderOptions* options) {
  CLI::App* cmd = app->add_subcommand(
      "render",
      "Render the 64x64 observation of a scene (black background, yellow ball, "
      "blue distractor on top; world (x,y) -> pixel (32+32x, 32+32y), +y down)");
  cmd->add_option("--ball", options->ball, "ball position X Y (world units)")
      ->expected(2)
      ->capture_default_str();
  cmd->add_option("--distractor", options->distractor, "distractor position X Y (world units)")
      ->expected(2)
      ->capture_default_str();
  cmd->add_option("-o,--output", options->output, "PNG file to write")->required();
  cmd->add_option("--scale", options->scale,
                  "upscale K times (nearest neighbour) for viewing; 1 is the true observation")
      ->capture_default_str();
  return cmd;
}

int run_render(const RenderOptions& options, std::FILE* err) {
  for (double v : options.ball) {
    if (!std::isfinite(v)) {
      std::fprintf(err, "curio-sim: --ball coordinates must be finite numbers\n");
      return 2;
    }
  }
  for (double v : options.distractor) {
    if (!std::isfinite(v)) {
      std::fprintf(err, "curio-sim: --distractor coordinates must be finite numbers\n");
      return 2;
    }
  }
  if (options.scale < 1 || options.scale > 64) {
    std::fprintf(err, "curio-sim: --scale must be between 1 and 64 (got %d)\n", options.scale);
    return 2;
  }
  Image image;
  render_scene({options.ball[0], options.ball[1]}, {options.distractor[0], options.distractor[1]},
               &image);

  const int k = options.scale;
  const int side = kImageSize * k;
  std::vector<float> scaled(static_cast<size_t>(side) * side * kImageChannels);
  for (int v = 0; v < side; ++v) {
    for (int u = 0; u < side; ++u) {
      for (int c = 0; c < kImageChannels; ++c) {
        scaled[(static_cast<size_t>(v) * side + u) * kImageChannels + c] =
            image[((v / k) * kImageSize + u / k) * kImageChannels + c];
      }
    }
  }
  std::string error;
  if (!write_png(options.output, scaled.data(), side, side, &error)) {
    std::fprintf(err, "curio-sim: %s\n", error.c_str());
    return 1;
  }
  return 0;
}

}  // namespace curio::sim
