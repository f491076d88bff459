#include "host_tools/encode/camera_png.hpp"

#include <sys/stat.h>

#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

#include <fmt/format.h>

namespace curio::encode {
namespace {

constexpr int kSide = nn::kImageSize;

// Weights of output index o over the source indices of one axis (n source pixels → kSide).
struct Taps {
  std::vector<std::vector<std::pair<int, double>>> taps;  // per output: (source index, weight)
};

Taps axis_taps(int n) {
  Taps t;
  t.taps.resize(kSide);
  const double scale = static_cast<double>(n) / kSide;
  for (int o = 0; o < kSide; ++o) {
    auto& out = t.taps[static_cast<size_t>(o)];
    if (scale >= 1.0) {  // shrink: the source interval [o·s, (o + 1)·s) averaged by coverage
      const double a = o * scale, b = (o + 1) * scale;
      for (int i = static_cast<int>(std::floor(a)); i < static_cast<int>(std::ceil(b)) && i < n; ++i) {
        const double w = std::min(b, i + 1.0) - std::max(a, static_cast<double>(i));
        if (w > 0) out.emplace_back(i, w / scale);
      }
    } else {  // enlarge: linear between source pixel centres, edges clamped
      const double x = (o + 0.5) * scale - 0.5;
      const int i0 = static_cast<int>(std::floor(x));
      const double f = x - i0;
      auto clamp = [n](int i) { return i < 0 ? 0 : (i >= n ? n - 1 : i); };
      out.emplace_back(clamp(i0), 1.0 - f);
      out.emplace_back(clamp(i0 + 1), f);
    }
  }
  return t;
}

struct PngRead {
  png_structp png = nullptr;
  png_infop info = nullptr;
  std::string error;
  ~PngRead() { png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr); }
};

void on_error(png_structp png, png_const_charp message) {
  auto* r = static_cast<PngRead*>(png_get_error_ptr(png));
  r->error = message;
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}

}  // namespace

CameraFrame resample_to_camera(const std::vector<uint8_t>& rgb, int width, int height) {
  const Taps tx = axis_taps(width), ty = axis_taps(height);
  std::vector<double> rows(static_cast<size_t>(height) * kSide * 3, 0.0);  // width resampled first
  for (int y = 0; y < height; ++y)
    for (int ox = 0; ox < kSide; ++ox)
      for (const auto& [x, w] : tx.taps[static_cast<size_t>(ox)])
        for (int c = 0; c < 3; ++c)
          rows[(static_cast<size_t>(y) * kSide + static_cast<size_t>(ox)) * 3 + static_cast<size_t>(c)] +=
              w * rgb[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 3 + static_cast<size_t>(c)];
  CameraFrame frame{};
  for (int oy = 0; oy < kSide; ++oy)
    for (int ox = 0; ox < kSide; ++ox)
      for (int c = 0; c < 3; ++c) {
        double v = 0.0;
        for (const auto& [y, w] : ty.taps[static_cast<size_t>(oy)])
          v += w * rows[(static_cast<size_t>(y) * kSide + static_cast<size_t>(ox)) * 3 + static_cast<size_t>(c)];
        const long r = std::lround(v);
        frame[(static_cast<size_t>(oy) * kSide + static_cast<size_t>(ox)) * 3 + static_cast<size_t>(c)] =
            static_cast<uint8_t>(r < 0 ? 0 : (r > 255 ? 255 : r));
      }
  return frame;
}

std::string read_camera_png(const std::string& path, bool resize, CameraImage* out) {
  auto fail = [&path](const std::string& why) { return path + ": " + why; };
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))  // a FIFO would hang the read
    return fail(S_ISDIR(st.st_mode) ? "a directory, not a PNG file" : "not a regular file (a FIFO or a device), not a PNG file");
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) return fail(std::string("cannot open (") + std::strerror(errno) + ")");
  png_byte signature[8] = {};
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0)
    return fail("not a PNG file");
  PngRead r;
  r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r, on_error, on_warning);
  if (r.png == nullptr) return fail("libpng could not start");
  r.info = png_create_info_struct(r.png);
  if (r.info == nullptr) return fail("libpng could not start");
  std::vector<uint8_t> rgb;
  std::vector<png_bytep> row_pointers;
  png_uint_32 width = 0, height = 0;
  if (setjmp(png_jmpbuf(r.png))) return fail("truncated or corrupt PNG (" + r.error + ")");
  png_init_io(r.png, file.get());
  png_set_sig_bytes(r.png, 8);
  png_read_info(r.png, r.info);
  width = png_get_image_width(r.png, r.info);
  height = png_get_image_height(r.png, r.info);
  const int depth = png_get_bit_depth(r.png, r.info);
  const int color = png_get_color_type(r.png, r.info);
  if (color == PNG_COLOR_TYPE_GRAY || color == PNG_COLOR_TYPE_GRAY_ALPHA)
    return fail("greyscale PNG; the encoder takes RGB, as the camera gives (save it as 8-bit RGB)");
  if (depth == 16) return fail("16-bit PNG; the encoder takes 8 bits per channel, as the camera gives");
  if ((color & PNG_COLOR_MASK_ALPHA) != 0 || png_get_valid(r.png, r.info, PNG_INFO_tRNS) != 0)
    return fail("PNG with an alpha channel; the encoder takes RGB, as the camera gives (save it without alpha)");
  // A palette image is read as its indices, each checked against the palette (libpng would
  // expand an index beyond it to black without a word), then expanded here.
  const bool palette = color == PNG_COLOR_TYPE_PALETTE;
  png_colorp palette_entries = nullptr;
  int palette_size = 0;
  if (palette && png_get_PLTE(r.png, r.info, &palette_entries, &palette_size) == 0)
    return fail("palette PNG without a palette (PLTE chunk)");
  if (depth < 8) png_set_packing(r.png);
  if (!resize && (width != static_cast<png_uint_32>(kSide) || height != static_cast<png_uint_32>(kSide)))
    return fail(fmt::format("{}×{} pixels; the encoder takes {}×{} (add --resize to resample it)", width, height,
                            kSide, kSide));
  if (width > 4096 || height > 4096)  // bounds the memory a damaged or hostile header can ask for
    return fail(fmt::format("{}×{} pixels; --resize takes images up to 4096×4096", width, height));
  png_set_interlace_handling(r.png);
  png_read_update_info(r.png, r.info);
  const size_t channels = palette ? 1 : 3;
  if (png_get_rowbytes(r.png, r.info) != static_cast<size_t>(width) * channels)
    return fail("unsupported PNG layout (not 3 bytes per pixel after expansion)");
  rgb.resize(static_cast<size_t>(width) * height * 3);
  row_pointers.resize(height);
  for (png_uint_32 y = 0; y < height; ++y)
    row_pointers[y] = rgb.data() + static_cast<size_t>(y) * width * channels;
  png_read_image(r.png, row_pointers.data());
  png_read_end(r.png, nullptr);
  if (palette) {  // indices in the first width·height bytes: expand from the last pixel back
    const size_t pixels = static_cast<size_t>(width) * height;
    for (size_t i = 0; i < pixels; ++i)
      if (rgb[i] >= palette_size)
        return fail(fmt::format("palette index {} at pixel ({}, {}) is beyond its {}-entry palette (a "
                                "corrupt PNG)",
                                rgb[i], i % width, i / width, palette_size));
    for (size_t i = pixels; i-- > 0;) {
      const png_color c = palette_entries[rgb[i]];
      rgb[i * 3] = c.red;
      rgb[i * 3 + 1] = c.green;
      rgb[i * 3 + 2] = c.blue;
    }
  }
  out->path = path;
  out->source_width = static_cast<int>(width);
  out->source_height = static_cast<int>(height);
  out->resized = width != static_cast<png_uint_32>(kSide) || height != static_cast<png_uint_32>(kSide);
  if (out->resized) {
    out->frame = resample_to_camera(rgb, static_cast<int>(width), static_cast<int>(height));
  } else {
    std::memcpy(out->frame.data(), rgb.data(), out->frame.size());
  }
  return "";
}

}  // namespace curio::encode
