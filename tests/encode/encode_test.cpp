// curio-encode's reading and encoding (host_tools/encode/): a rendered scene saved as a PNG
// gives the camera frame the arm's camera would send and the μ the controller's encoder
// computes from it; every kind of bad input is refused with one line naming the file;
// --resize's box filter undoes an integer upscale exactly; the float decoder reconstructs a
// scene the model has seen close to the original.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <png.h>
#include <zlib.h>

#include "firmware/nn/encoder.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "host_tools/encode/camera_png.hpp"
#include "host_tools/encode/encode_images.hpp"
#include "sim/render.hpp"

namespace curio::encode {
namespace {

namespace fs = std::filesystem;

class EncodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("curio_encode_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // A PNG written by libpng with the given colour type and bit depth, `fill` in every sample.
  std::string write_raw_png(const std::string& name, int w, int h, int color, int depth, int fill = 0x80) {
    const std::string p = path(name);
    FILE* f = std::fopen(p.c_str(), "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), depth, color,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    const int channels = color == PNG_COLOR_TYPE_GRAY ? 1 : (color == PNG_COLOR_TYPE_RGBA ? 4 : 3);
    std::vector<uint8_t> row(static_cast<size_t>(w * channels * depth / 8), static_cast<uint8_t>(fill));
    for (int y = 0; y < h; ++y) png_write_row(png, row.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return p;
  }

  fs::path dir_;
};

sim::Image scene(double bx, double by, double dx, double dy) {
  sim::Image img{};
  sim::render_scene({bx, by}, {dx, dy}, &img);
  return img;
}

TEST_F(EncodeTest, ARenderedSceneGivesTheCameraFrameAndTheControllersMu) {
  const GoalSpace space("beta_vae", CURIO_MODELS_DIR);
  ASSERT_TRUE(space.has_float()) << space.float_note();
  nn::Encoder controller_encoder(*space.representation().model);
  for (const auto& [bx, by, dx, dy] : std::vector<std::array<double, 4>>{{0.3, -0.2, -0.5, 0.4}, {-0.7, 0.6, 0.1, 0.1}}) {
    const sim::Image img = scene(bx, by, dx, dy);
    std::string error;
    ASSERT_TRUE(sim::write_png(path("scene.png"), img.data(), 64, 64, &error)) << error;
    CameraImage read;
    ASSERT_EQ(read_camera_png(path("scene.png"), false, &read), "");
    // The camera's bytes: round(255·v) per value (protocol::camera_pixel).
    CameraFrame camera{};
    for (size_t i = 0; i < camera.size(); ++i) camera[i] = protocol::camera_pixel(img[i]);
    EXPECT_EQ(read.frame, camera);
    EXPECT_FALSE(read.resized);
    float mu[nn::kLatents], log_var[nn::kLatents];
    ASSERT_EQ(controller_encoder.encode(camera.data(), mu, log_var), nn::Status::kOk);
    const ImageCodes codes = space.encode(read);
    for (size_t l = 0; l < nn::kLatents; ++l) {
      EXPECT_EQ(codes.mu_int8[l], mu[l]) << "z" << l;  // bit for bit: the same encoder, same bytes
      EXPECT_EQ(codes.log_var_int8[l], log_var[l]) << "z" << l;
      EXPECT_NEAR(codes.mu_float[l], mu[l], 0.05) << "z" << l;  // int8 within its measured error
    }
    // The two modules that move with this scene are the active ones (the ball's and the
    // distractor's pairs), the collapsed latents' modules carry no KL.
    ASSERT_EQ(codes.module_activity.size(), 5u);
    EXPECT_GT(codes.module_activity[0], 1.0);
    EXPECT_GT(codes.module_activity[1], 1.0);
    for (size_t m = 2; m < 5; ++m) EXPECT_LT(codes.module_activity[m], 0.5) << m;
  }
}

TEST_F(EncodeTest, BadInputIsRefusedWithOneLineNamingTheFile) {
  const std::string ok_rgb = write_raw_png("ok.png", 64, 64, PNG_COLOR_TYPE_RGB, 8);
  CameraImage image;
  EXPECT_EQ(read_camera_png(ok_rgb, false, &image), "");
  std::ofstream(path("text.png")) << "not a png at all";
  {
    std::ifstream in(ok_rgb, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(path("truncated.png"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  const std::vector<std::pair<std::string, std::string>> cases{
      {path("text.png"), "not a PNG file"},
      {path("truncated.png"), "truncated or corrupt PNG"},
      {write_raw_png("grey.png", 64, 64, PNG_COLOR_TYPE_GRAY, 8), "greyscale PNG"},
      {write_raw_png("deep.png", 64, 64, PNG_COLOR_TYPE_RGB, 16), "16-bit PNG"},
      {write_raw_png("rgba.png", 64, 64, PNG_COLOR_TYPE_RGBA, 8), "alpha channel"},
      {write_raw_png("small.png", 32, 48, PNG_COLOR_TYPE_RGB, 8), "32×48 pixels; the encoder takes 64×64 (add --resize"},
      {path("missing.png"), "cannot open"},
  };
  for (const auto& [file, expected] : cases) {
    const std::string why = read_camera_png(file, false, &image);
    EXPECT_EQ(why.rfind(file + ": ", 0), 0u) << why;
    EXPECT_NE(why.find(expected), std::string::npos) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;
  }
  // --resize takes another size, not another format.
  EXPECT_EQ(read_camera_png(path("small.png"), true, &image), "");
  EXPECT_TRUE(image.resized);
  EXPECT_NE(read_camera_png(path("grey.png"), true, &image), "");
}

// A palette PNG: each index is checked against its palette (libpng alone expands an index
// beyond it to black without a word); indices within it give the palette's colours.
TEST_F(EncodeTest, PaletteIndicesBeyondThePaletteAreRefused) {
  const auto write_palette_png = [&](const std::string& name, uint8_t index) {
    const std::string p = path(name);
    FILE* f = std::fopen(p.c_str(), "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, 64, 64, 8, PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_color palette[4] = {{10, 20, 30}, {40, 50, 60}, {70, 80, 90}, {200, 210, 220}};
    png_set_PLTE(png, info, palette, 4);
    png_set_check_for_invalid_index(png, 0);  // write the bad index as a damaged file has it
    png_write_info(png, info);
    std::vector<uint8_t> row(64, 2);
    for (int y = 0; y < 64; ++y) {
      row[5] = y == 9 ? index : 3;
      png_write_row(png, row.data());
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return p;
  };
  CameraImage image;
  ASSERT_EQ(read_camera_png(write_palette_png("ok.png", 1), false, &image), "");
  EXPECT_EQ(image.frame[0], 70);
  EXPECT_EQ(image.frame[2], 90);
  EXPECT_EQ(image.frame[(9 * 64 + 5) * 3 + 1], 50);
  EXPECT_EQ(image.frame[(8 * 64 + 5) * 3 + 2], 220);
  const std::string bad = write_palette_png("beyond.png", 7);
  EXPECT_EQ(read_camera_png(bad, false, &image),
            bad + ": palette index 7 at pixel (5, 9) is beyond its 4-entry palette (a corrupt PNG)");
}

TEST_F(EncodeTest, ResizeUndoesAnIntegerUpscaleExactly) {
  CameraFrame original{};
  for (size_t i = 0; i < original.size(); ++i) original[i] = static_cast<uint8_t>((i * 37 + i / 7) & 0xFF);
  for (int k : {2, 3}) {
    std::vector<uint8_t> big(static_cast<size_t>(64 * k * 64 * k * 3));
    for (int y = 0; y < 64 * k; ++y)
      for (int x = 0; x < 64 * k; ++x)
        for (int c = 0; c < 3; ++c)
          big[(static_cast<size_t>(y) * static_cast<size_t>(64 * k) + static_cast<size_t>(x)) * 3 + static_cast<size_t>(c)] =
              original[(static_cast<size_t>(y / k) * 64 + static_cast<size_t>(x / k)) * 3 + static_cast<size_t>(c)];
    EXPECT_EQ(resample_to_camera(big, 64 * k, 64 * k), original) << "upscaled ×" << k;
  }
  // Enlarging (and shrinking by a non-integer factor) a uniform image keeps it uniform.
  std::vector<uint8_t> flat(static_cast<size_t>(10 * 20 * 3), 200);
  const CameraFrame f = resample_to_camera(flat, 10, 20);
  for (uint8_t v : f) EXPECT_EQ(v, 200);
}

// The scene rendered at a camera's size (sim::render_scene with a width and height, what
// curio-sim serve --camera-stream sends) and resampled as curio-controller --camera does gives
// the 64×64 render within one step per byte: the same field of view, square pixels, the exact
// coverages averaged (only each render's own rounding to bytes differs). 64×64 is the render
// itself, and a 4:3 frame sees the same square in its middle.
TEST_F(EncodeTest, ASceneRenderedAtACameraSizeResamplesToThe64x64Render) {
  const sim::Vec2 ball{0.31, -0.27}, distractor{-0.58, 0.44};
  sim::Image small{};
  sim::render_scene(ball, distractor, &small);
  CameraFrame expected{};
  for (size_t i = 0; i < expected.size(); ++i) expected[i] = protocol::camera_pixel(small[i]);
  const auto frame_at = [&](int w, int h) {
    std::vector<float> hwc(static_cast<size_t>(w * h * 3));
    sim::render_scene(ball, distractor, w, h, hwc.data());
    std::vector<uint8_t> bytes(hwc.size());
    for (size_t i = 0; i < hwc.size(); ++i) bytes[i] = protocol::camera_pixel(hwc[i]);
    return bytes;
  };
  EXPECT_EQ(resample_to_camera(frame_at(64, 64), 64, 64), expected);
  // An integer multiple averages whole pixels: the same coverages, up to each render's rounding.
  // Another size splits source pixels, each taken as uniform: the disc's edges blur a little.
  for (int side : {128, 192, 320, 120, 96}) {
    const CameraFrame f = resample_to_camera(frame_at(side, side), side, side);
    int worst = 0;
    double sum = 0;
    for (size_t i = 0; i < f.size(); ++i) {
      worst = std::max(worst, std::abs(f[i] - expected[i]));
      sum += std::abs(f[i] - expected[i]);
    }
    std::printf("%dx%d resampled to 64x64: largest byte difference %d, mean %.3f\n", side, side, worst,
                sum / static_cast<double>(f.size()));
    if (side % 64 == 0) {
      EXPECT_LE(worst, 1) << side << "x" << side;
    }
    EXPECT_LE(sum / static_cast<double>(f.size()), 0.5) << side << "x" << side;
  }
  // 160×120: the middle 120×120 is the 120×120 render (up to the last bit of the centre's
  // coordinate, computed from another origin).
  const std::vector<uint8_t> wide = frame_at(160, 120), square = frame_at(120, 120);
  int worst = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 120 * 3; ++x)
      worst = std::max(worst, std::abs(wide[static_cast<size_t>(y * 160 * 3 + 20 * 3 + x)] -
                                       square[static_cast<size_t>(y * 120 * 3 + x)]));
  EXPECT_LE(worst, 1);
}

TEST_F(EncodeTest, TheFloatDecoderReconstructsASceneCloseToIt) {
  const GoalSpace space("beta_vae", CURIO_MODELS_DIR);
  ASSERT_TRUE(space.has_decoder()) << space.float_note();
  const sim::Image img = scene(0.3, -0.2, -0.5, 0.4);
  CameraImage image;
  for (size_t i = 0; i < image.frame.size(); ++i) image.frame[i] = protocol::camera_pixel(img[i]);
  const ImageCodes codes = space.encode(image);
  const std::vector<float> recon = space.decode(codes.mu_float);
  double err = 0.0, err_blank = 0.0;
  for (size_t i = 0; i < recon.size(); ++i) {
    err += std::abs(recon[i] - img[i]);
    err_blank += std::abs(img[i]);  // a black image's error: what "close" is measured against
  }
  EXPECT_LT(err, 0.35 * err_blank) << "mean abs error " << err / static_cast<double>(recon.size());
  // A decoding with the ball's latents moved puts the ball elsewhere: the pixels change.
  Latents z = codes.mu_float;
  z[static_cast<size_t>(space.modules()[0][0])] += 2.0f;
  const std::vector<float> moved = space.decode(z);
  double change = 0.0;
  for (size_t i = 0; i < moved.size(); ++i) change += std::abs(moved[i] - recon[i]);
  EXPECT_GT(change, 0.3 * err_blank);
}

TEST(EncodeGoalSpace, ManyImagesOnSeveralThreadsGiveEachImagesOwnCodes) {
  const GoalSpace space("beta_vae", CURIO_MODELS_DIR);
  std::vector<CameraImage> images(7);
  for (size_t i = 0; i < images.size(); ++i) {
    const sim::Image img = scene(-0.8 + 0.25 * static_cast<double>(i), 0.5 - 0.15 * static_cast<double>(i), 0.6, -0.3);
    for (size_t k = 0; k < images[i].frame.size(); ++k) images[i].frame[k] = protocol::camera_pixel(img[k]);
    images[i].path = "scene" + std::to_string(i);
  }
  for (int threads : {1, 3}) {
    const std::vector<ImageCodes> all = space.encode_all(images, threads);
    ASSERT_EQ(all.size(), images.size());
    for (size_t i = 0; i < images.size(); ++i) {
      const ImageCodes one = space.encode(images[i]);
      EXPECT_EQ(all[i].mu_int8, one.mu_int8) << threads << " threads, image " << i;
      EXPECT_EQ(all[i].log_var_int8, one.log_var_int8) << threads << " threads, image " << i;
      EXPECT_EQ(all[i].mu_float, one.mu_float);
      EXPECT_EQ(all[i].image.path, images[i].path);
    }
  }
  EXPECT_TRUE(space.encode_all({}, 2).empty());
}

TEST(EncodeGoalSpace, AnUnknownModelIsRefusedNamingTheKnownOnes) {
  try {
    GoalSpace space("gan", CURIO_MODELS_DIR);
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("known: beta_vae"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace curio::encode
