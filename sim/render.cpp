#include "sim/render.hpp"

#include <algorithm>

#include "sim/disc_coverage.hpp"
#include "sim/scene.hpp"

namespace curio::sim {
namespace {

struct Colour {
  float r, g, b;
};

// Source-over with the coverage as alpha: dst = colour·a + dst·(1 − a). The world's origin at
// the image's centre, `ppu` pixels per world unit (64×64: u = 32 + 32x).
void draw_disc(const Vec2& centre, double radius, Colour colour, int width, int height, double ppu,
               float* image) {
  const double cu = width / 2.0 + ppu * centre.x;
  const double cv = height / 2.0 + ppu * centre.y;
  for_each_covered_pixel(cu, cv, radius * ppu, width, height,
                         [&](int row, int col, double coverage) {
                           const auto a = static_cast<float>(coverage);
                           float* px = image + (row * width + col) * kImageChannels;
                           px[0] = colour.r * a + px[0] * (1.0f - a);
                           px[1] = colour.g * a + px[1] * (1.0f - a);
                           px[2] = colour.b * a + px[2] * (1.0f - a);
                         });
}

}  // namespace

void render_scene(const Vec2& ball, const Vec2& distractor, Image* out) {
  render_scene(ball, distractor, kImageSize, kImageSize, out->data());
}

void render_scene(const Vec2& ball, const Vec2& distractor, int width, int height, float* hwc) {
  const double ppu = (width < height ? width : height) / 2.0;
  std::fill(hwc, hwc + static_cast<size_t>(width) * static_cast<size_t>(height) * kImageChannels, 0.0f);
  draw_disc(ball, kBallRadius, {1.0f, 1.0f, 0.0f}, width, height, ppu, hwc);
  draw_disc(distractor, kDistractorRadius, {0.0f, 0.0f, 1.0f}, width, height, ppu, hwc);
}

}  // namespace curio::sim
