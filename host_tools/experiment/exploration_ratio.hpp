// The exploration metric of SPEC §4: the fraction of the 900 cells of a 30×30 grid over
// [-1,1]² that hold at least one final ball position. Updated one episode at a time.
#pragma once
#include <array>
#include <cstdint>

namespace curio::lab {

class ExplorationRatio {
 public:
  static constexpr int kCellsPerSide = 30;
  static constexpr int kCells = kCellsPerSide * kCellsPerSide;

  // Adds one final ball position; positions outside [-1,1]² count in no cell.
  void add(double x, double y) {
    const int cx = cell_of(x);
    const int cy = cell_of(y);
    if (cx < 0 || cy < 0) return;
    auto& hit = visited_[static_cast<std::size_t>(cy * kCellsPerSide + cx)];
    if (!hit) {
      hit = 1;
      ++visited_count_;
    }
  }

  double ratio() const { return static_cast<double>(visited_count_) / kCells; }
  int visited_cells() const { return visited_count_; }

  // Cell index along one axis: [-1,1] cut in 30 equal bins, 1.0 falls in the last one.
  static int cell_of(double v) {
    if (!(v >= -1.0 && v <= 1.0)) return -1;
    const int c = static_cast<int>((v + 1.0) * 0.5 * kCellsPerSide);
    return c >= kCellsPerSide ? kCellsPerSide - 1 : c;
  }

 private:
  std::array<uint8_t, kCells> visited_{};
  int visited_count_ = 0;
};

}  // namespace curio::lab
