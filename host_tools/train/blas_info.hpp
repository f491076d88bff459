// Which BLAS this process really runs on: Debian's libtorch goes through libblas.so.3,
// and the reference BLAS behind it makes training 4–5× slower than OpenBLAS (measured here).
#pragma once
#include <string>

namespace curio::train {

struct BlasInfo {
  std::string library;  // resolved path of the mapped BLAS library ("" if none mapped yet)
  bool openblas = false;
  bool reference = false;  // Netlib reference BLAS: slow
};

// Reads /proc/self/maps (call after LibTorch has run a matrix product, so BLAS is mapped).
BlasInfo detect_blas();

}  // namespace curio::train
