#include "host_tools/encode/camera_png.hpp"

#include <sys/stat.h>

#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

#include <fmt/format.h>

#include "host_tools/experiment/camera_resample.hpp"

namespace curio::encode {
namespace {

constexpr int kSide = nn::kImageSize;

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
  CameraFrame frame{};
  lab::resample_to_camera(rgb.data(), width, height, frame.data());
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
