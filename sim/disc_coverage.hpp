// Exact anti-aliasing of a disc: the area of its intersection with each unit pixel
// square [u, u+1] × [v, v+1], computed analytically (no supersampling) and only over
// the disc's bounding box.
#pragma once
#include <algorithm>
#include <cmath>

namespace curio::sim {

// Antiderivative in x of the disc's chord length above the line y = h (disc centred at
// the origin, radius r), so that area(disc ∩ [x0, x1] × [h, ∞)) = Q(x1, h) − Q(x0, h).
inline double disc_area_above_antiderivative(double x, double h, double r) {
  if (h < 0.0) {
    // Above a negative h = the whole strip minus its mirror image above −h.
    return 2.0 * disc_area_above_antiderivative(x, 0.0, r) -
           disc_area_above_antiderivative(x, -h, r);
  }
  if (h >= r) return 0.0;
  const double half_chord = std::sqrt(r * r - h * h);
  x = std::clamp(x, -half_chord, half_chord);
  const double y = std::sqrt(std::max(0.0, r * r - x * x));
  const double s = std::clamp(x / r, -1.0, 1.0);
  return 0.5 * (x * y + r * r * std::asin(s)) - h * x;
}

// Calls visit(row, col, coverage) for every pixel of a width × height grid that the disc
// (centre (cu, cv), radius r, all in pixel units) touches; coverage ∈ [0, 1] is the
// exact covered fraction of the pixel.
template <typename Visit>
void for_each_covered_pixel(double cu, double cv, double r, int width, int height, Visit visit) {
  constexpr int kMaxSpan = 64;  // bounding boxes beyond this are clipped to the image anyway
  const int col0 = std::max(0, static_cast<int>(std::floor(cu - r)));
  const int col1 = std::min(width, static_cast<int>(std::ceil(cu + r)));  // exclusive
  const int row0 = std::max(0, static_cast<int>(std::floor(cv - r)));
  const int row1 = std::min(height, static_cast<int>(std::ceil(cv + r)));
  if (col0 >= col1 || row0 >= row1 || col1 - col0 > kMaxSpan) return;

  // Q at every column edge for the current and the next row edge.
  double q_top[kMaxSpan + 1];
  double q_bottom[kMaxSpan + 1];
  const int edges = col1 - col0 + 1;
  auto fill = [&](int row_edge, double* q) {
    const double h = static_cast<double>(row_edge) - cv;
    for (int e = 0; e < edges; ++e) {
      q[e] = disc_area_above_antiderivative(static_cast<double>(col0 + e) - cu, h, r);
    }
  };
  fill(row0, q_top);
  for (int row = row0; row < row1; ++row) {
    fill(row + 1, q_bottom);
    for (int e = 0; e + 1 < edges; ++e) {
      const double area = (q_top[e + 1] - q_top[e]) - (q_bottom[e + 1] - q_bottom[e]);
      if (area > 0.0) visit(row, col0 + e, std::min(area, 1.0));
    }
    std::copy(q_bottom, q_bottom + edges, q_top);
  }
}

}  // namespace curio::sim
