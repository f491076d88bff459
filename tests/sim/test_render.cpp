// The observation image (SPEC §1.4): exact coverage, colours, layering, pixel mapping.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "firmware/explore/fnv1a.hpp"
#include "firmware/explore/prng.hpp"
#include "sim/disc_coverage.hpp"
#include "sim/render.hpp"
#include "sim/scene.hpp"

namespace curio::sim {
namespace {

constexpr Vec2 kOffImage{10.0, 10.0};
constexpr double kPi = 3.14159265358979323846;

float channel(const Image& image, int row, int col, int c) {
  return image[(row * kImageSize + col) * kImageChannels + c];
}

double channel_sum(const Image& image, int c) {
  double sum = 0.0;
  for (int i = c; i < kImageValues; i += kImageChannels) sum += image[i];
  return sum;
}

TEST(Render, DiscCoverageSumsToItsArea) {
  Prng rng(4);
  for (int i = 0; i < 50; ++i) {
    const Vec2 ball{rng.uniform(-0.8, 0.8), rng.uniform(-0.8, 0.8)};
    Image image;
    render_scene(ball, kOffImage, &image);
    const double r_px = 0.17 * 32;
    EXPECT_NEAR(channel_sum(image, 0) / (kPi * r_px * r_px), 1.0, 1e-6);  // float storage
    EXPECT_EQ(channel_sum(image, 2), 0.0);
    render_scene(kOffImage, ball, &image);
    const double d_px = 0.15 * 32;
    EXPECT_NEAR(channel_sum(image, 2) / (kPi * d_px * d_px), 1.0, 1e-6);
  }
}

// Coverage of one pixel by 1-D numerical integration of the chord: an independent check.
double numeric_coverage(double cu, double cv, double r, int row, int col) {
  constexpr int kSlices = 20000;
  double area = 0.0;
  for (int i = 0; i < kSlices; ++i) {
    const double u = col + (i + 0.5) / kSlices - cu;
    if (std::fabs(u) >= r) continue;
    const double h = std::sqrt(r * r - u * u);
    const double lo = std::max(cv - h, static_cast<double>(row));
    const double hi = std::min(cv + h, static_cast<double>(row + 1));
    if (hi > lo) area += (hi - lo) / kSlices;
  }
  return area;
}

TEST(DiscCoverage, MatchesNumericalIntegrationPerPixel) {
  Prng rng(8);
  for (int i = 0; i < 6; ++i) {
    const double cu = rng.uniform(10.0, 54.0);
    const double cv = rng.uniform(10.0, 54.0);
    const double r = 5.44;
    int pixels = 0;
    double total = 0.0;
    for_each_covered_pixel(cu, cv, r, kImageSize, kImageSize, [&](int row, int col, double a) {
      EXPECT_NEAR(a, numeric_coverage(cu, cv, r, row, col), 1e-6) << row << "," << col;
      ++pixels;
      total += a;
    });
    EXPECT_GT(pixels, 90);
    EXPECT_NEAR(total, kPi * r * r, 1e-9);
  }
}

TEST(DiscCoverage, ClippedAtTheImageBorder) {
  // A disc centred on the image corner: a quarter of it lies inside.
  double total = 0.0;
  for_each_covered_pixel(0.0, 0.0, 5.0, kImageSize, kImageSize, [&](int row, int col, double a) {
    ASSERT_GE(row, 0);
    ASSERT_GE(col, 0);
    total += a;
  });
  EXPECT_NEAR(total, kPi * 25.0 / 4.0, 1e-9);
}

TEST(Render, ExactColoursAndBlackBackground) {
  Image image;
  const Vec2 ball{-0.5, -0.5};      // pixel centre (16, 16)
  const Vec2 distractor{0.5, 0.5};  // pixel centre (48, 48)
  render_scene(ball, distractor, &image);
  EXPECT_EQ(channel(image, 16, 16, 0), 1.0f);
  EXPECT_EQ(channel(image, 16, 16, 1), 1.0f);
  EXPECT_EQ(channel(image, 16, 16, 2), 0.0f);
  EXPECT_EQ(channel(image, 48, 48, 0), 0.0f);
  EXPECT_EQ(channel(image, 48, 48, 1), 0.0f);
  EXPECT_EQ(channel(image, 48, 48, 2), 1.0f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(channel(image, 0, 63, c), 0.0f);
    EXPECT_EQ(channel(image, 32, 32, c), 0.0f);
  }
  for (float v : image) {
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
  }
}

TEST(Render, DistractorIsDrawnOnTopOfTheBall) {
  Image image;
  render_scene({0.0, 0.0}, {0.0, 0.0}, &image);
  // Where the distractor fully covers: pure blue.
  EXPECT_EQ(channel(image, 32, 32, 0), 0.0f);
  EXPECT_EQ(channel(image, 32, 32, 2), 1.0f);
  // Partial overlap: ball·(1 − d) in red/green, d in blue.
  render_scene({0.0, 0.0}, {0.2, 0.0}, &image);
  const int row = 32;
  bool checked = false;
  for (int col = 32; col < 44; ++col) {
    const float ball = 1.0f;  // ball covers columns ≤ 36 fully on row 32
    const float d = channel(image, row, col, 2);
    if (col <= 36 && d > 0.0f && d < 1.0f) {
      EXPECT_FLOAT_EQ(channel(image, row, col, 0), ball * (1.0f - d));
      EXPECT_FLOAT_EQ(channel(image, row, col, 1), ball * (1.0f - d));
      checked = true;
    }
  }
  EXPECT_TRUE(checked);
}

TEST(Render, PlusYPointsDown) {
  Image image;
  render_scene({0.0, 0.5}, kOffImage, &image);  // centre column 32, row 48
  EXPECT_EQ(channel(image, 48, 31, 0), 1.0f);
  EXPECT_EQ(channel(image, 48, 32, 0), 1.0f);
  EXPECT_EQ(channel(image, 16, 32, 0), 0.0f);
  // Symmetric about the pixel edge u = 32: columns 31 and 32 mirror each other.
  for (int row = 40; row < 56; ++row) {
    EXPECT_NEAR(channel(image, row, 31 - 3, 0), channel(image, row, 32 + 3, 0), 1e-6);
  }
  render_scene({0.5, 0.0}, kOffImage, &image);  // +x to the right
  EXPECT_EQ(channel(image, 32, 48, 0), 1.0f);
  EXPECT_EQ(channel(image, 32, 16, 0), 0.0f);
}

TEST(WritePng, RoundTripsThroughLibpng) {
  Image image;
  render_scene({-0.5, -0.5}, {0.5, 0.5}, &image);
  const auto path = std::filesystem::temp_directory_path() / "curio_sim_test_render.png";
  std::string error;
  ASSERT_TRUE(write_png(path.string(), image.data(), kImageSize, kImageSize, &error)) << error;

  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&png, path.string().c_str()));
  png.format = PNG_FORMAT_RGB;
  EXPECT_EQ(png.width, 64u);
  EXPECT_EQ(png.height, 64u);
  std::vector<unsigned char> bytes(PNG_IMAGE_SIZE(png));
  ASSERT_TRUE(png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr));
  const auto at = [&](int row, int col, int c) { return bytes[(row * 64 + col) * 3 + c]; };
  EXPECT_EQ(at(16, 16, 0), 255);
  EXPECT_EQ(at(16, 16, 2), 0);
  EXPECT_EQ(at(48, 48, 2), 255);
  EXPECT_EQ(at(0, 0, 0), 0);
  std::filesystem::remove(path);

  EXPECT_FALSE(write_png("/nonexistent-dir/x.png", image.data(), 64, 64, &error));
  EXPECT_FALSE(error.empty());
}

// The images of renderer version 1, pinned: 200 scenes drawn from a fixed stream, each pixel
// at 8 bits (as PNG and the encoder's input see it), hashed. The renderer's version is part of
// the simulated world's identity, which curio-controller compares with the arm's: a change to
// what a scene looks like must raise kRendererVersion, and this test says so.
TEST(Render, ImagesOfThisRendererVersionArePinned) {
  Prng prng(2024);
  Fnv1a hash;
  Image image;
  for (int i = 0; i < 200; ++i) {
    const Vec2 ball{prng.uniform01() * 2.2 - 1.1, prng.uniform01() * 2.2 - 1.1};
    const Vec2 distractor{prng.uniform01() * 2.2 - 1.1, prng.uniform01() * 2.2 - 1.1};
    render_scene(ball, distractor, &image);
    for (float v : image) hash.add_u32(static_cast<uint32_t>(std::lround(v * 255.0f)));
  }
  static_assert(kRendererVersion == 1, "a new renderer version pins its own images here");
  EXPECT_EQ(hash.h, 0xfcb37d1fu)
      << "the rendered images changed: raise kRendererVersion (sim/render.hpp) and pin the new "
         "hash here";
}

}  // namespace
}  // namespace curio::sim
