#include "sim/cli/render_command.hpp"

#include <cmath>
#include <vector>

#include "host_tools/cli/command_line.hpp"
#include "sim/render.hpp"

namespace curio::sim {

namespace {

// One coordinate of --ball or --distractor. The image shows the arena [-1, 1]² (pixel
// u = 32 + 32x): every scene of the world lies in it (the ball within the arm's reach of 1, the
// distractor clamped to ±0.95). A position outside would be drawn partly or not at all,
// silently: refused.
const CLI::Validator kArenaCoordinate(
    [](std::string& text) {
      double v = 0.0;
      if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v))
        return "'" + text + "' is not a finite number";
      if (std::fabs(v) > 1.0)
        return text +
               " is outside the arena [-1, 1] x [-1, 1] that the image shows (no scene of the "
               "world lies there)";
      return std::string();
    },
    "X Y in [-1, 1]");

}  // namespace

CLI::App* add_render_command(CLI::App* app, RenderOptions* options) {
  CLI::App* cmd = app->add_subcommand(
      "render",
      "Render the 64x64 observation of a scene (black background, yellow ball, "
      "blue distractor on top; world (x,y) -> pixel (32+32x, 32+32y), +y down)");
  cmd->add_option("--ball", options->ball, "ball position X Y (world units)")
      ->expected(2)
      ->check(kArenaCoordinate)
      ->capture_default_str();
  cmd->add_option("--distractor", options->distractor, "distractor position X Y (world units)")
      ->expected(2)
      ->check(kArenaCoordinate)
      ->capture_default_str();
  cmd->add_option("--png", options->png, "PNG file to write")
      ->required()
      ->check(cli::kOutputFile);
  cmd->add_option("--scale", options->scale,
                  "upscale K times (nearest neighbour) for viewing; 1 is the true observation")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  return cmd;
}

int run_render(const RenderOptions& options, std::FILE* err) {
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
  if (!write_png(options.png, scaled.data(), side, side, &error)) {
    std::fprintf(err, "curio-sim: %s\n", error.c_str());
    return 1;
  }
  return 0;
}

}  // namespace curio::sim
