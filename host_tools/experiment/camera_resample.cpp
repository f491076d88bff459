#include "host_tools/experiment/camera_resample.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "firmware/nn/encoder_arch.hpp"

namespace curio::lab {
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

}  // namespace

void resample_to_camera(const uint8_t* rgb, int width, int height, uint8_t* frame) {
  const Taps tx = axis_taps(width), ty = axis_taps(height);
  std::vector<double> rows(static_cast<size_t>(height) * kSide * 3, 0.0);  // width resampled first
  for (int y = 0; y < height; ++y)
    for (int ox = 0; ox < kSide; ++ox)
      for (const auto& [x, w] : tx.taps[static_cast<size_t>(ox)])
        for (int c = 0; c < 3; ++c)
          rows[(static_cast<size_t>(y) * kSide + static_cast<size_t>(ox)) * 3 + static_cast<size_t>(c)] +=
              w * rgb[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 3 + static_cast<size_t>(c)];
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
}

}  // namespace curio::lab
