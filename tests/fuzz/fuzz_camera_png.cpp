// libFuzzer target: curio-encode's PNG reading (host_tools/encode/camera_png.hpp) on arbitrary
// bytes and on a valid 64×64 RGB PNG with bytes changed. Oracles beyond "no crash, no UB":
// a file either reads (then a 64×64 frame, resized exactly when its own size is not 64×64) or
// is refused with one line that starts with its path; without --resize only 64×64 reads.
#include <fuzzer/FuzzedDataProvider.h>

#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "host_tools/encode/camera_png.hpp"
#include "sim/render.hpp"
#include "tests/fuzz/fuzz_check.hpp"

namespace {

std::string temp_path() {
  return "/tmp/curio_fuzz_camera_" + std::to_string(getpid()) + ".png";
}

std::vector<uint8_t> valid_png() {
  static const std::vector<uint8_t> bytes = [] {
    curio::sim::Image img{};
    curio::sim::render_scene({0.3, -0.2}, {-0.5, 0.4}, &img);
    std::string error;
    const std::string p = temp_path();
    curio::sim::write_png(p, img.data(), 64, 64, &error);
    std::vector<uint8_t> b;
    if (FILE* f = std::fopen(p.c_str(), "rb")) {
      int c;
      while ((c = std::fgetc(f)) != EOF) b.push_back(static_cast<uint8_t>(c));
      std::fclose(f);
    }
    return b;
  }();
  return bytes;
}

void read_both_ways(const std::vector<uint8_t>& bytes) {
  const std::string p = temp_path();
  FILE* f = std::fopen(p.c_str(), "wb");
  if (f == nullptr) return;
  std::fwrite(bytes.data(), 1, bytes.size(), f);
  std::fclose(f);
  for (const bool resize : {false, true}) {
    curio::encode::CameraImage image;
    const std::string why = curio::encode::read_camera_png(p, resize, &image);
    if (why.empty()) {
      check(image.path == p);
      check(image.resized == (image.source_width != 64 || image.source_height != 64));
      check(resize || !image.resized);
    } else {
      check(why.rfind(p + ": ", 0) == 0);
      check(why.find('\n') == std::string::npos);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  if (in.ConsumeBool()) {
    read_both_ways(in.ConsumeRemainingBytes<uint8_t>());
    return 0;
  }
  std::vector<uint8_t> bytes = valid_png();
  const int changes = in.ConsumeIntegralInRange<int>(1, 4);
  for (int i = 0; i < changes && !bytes.empty(); ++i)
    bytes[in.ConsumeIntegralInRange<size_t>(0, bytes.size() - 1)] = in.ConsumeIntegral<uint8_t>();
  if (in.ConsumeBool() && !bytes.empty()) bytes.resize(in.ConsumeIntegralInRange<size_t>(0, bytes.size()));
  read_both_ways(bytes);
  return 0;
}
