#include "sim/render.hpp"

#include <algorithm>

#include "sim/disc_coverage.hpp"
#include "sim/scene.hpp"

namespace curio::sim {
namespace {

constexpr double kPixelsPerUnit = kImageSize / 2.0;  // u = 32 + 32x

struct Colour {
  float r, g, b;
};

// Source-over with the coverage as alpha: dst = colour·a + dst·(1 − a).
void draw_disc(const Vec2& centre, double radius, Colour colour, Image* image) {
  const double cu = kPixelsPerUnit + kPixelsPerUnit * centre.x;
  const double cv = kPixelsPerUnit + kPixelsPerUnit * centre.y;
  for_each_covered_pixel(cu, cv, radius * kPixelsPerUnit, kImageSize, kImageSize,
                         [&](int row, int col, double coverage) {
                           const auto a = static_cast<float>(coverage);
                           float* px = image->data() + (row * kImageSize + col) * kImageChannels;
                           px[0] = colour.r * a + px[0] * (1.0f - a);
                           px[1] = colour.g * a + px[1] * (1.0f - a);
                           px[2] = colour.b * a + px[2] * (1.0f - a);
                         });
}

}  // namespace

void render_scene(const Vec2& ball, const Vec2& distractor, Image* out) {
  out->fill(0.0f);
  draw_disc(ball, kBallRadius, {1.0f, 1.0f, 0.0f}, out);
  draw_disc(distractor, kDistractorRadius, {0.0f, 0.0f, 1.0f}, out);
}

}  // namespace curio::sim
