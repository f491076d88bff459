#include "host_tools/train/blas_info.hpp"

#include <filesystem>
#include <fstream>

namespace curio::train {

BlasInfo detect_blas() {
  BlasInfo info;
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    const auto slash = line.find('/');
    if (slash == std::string::npos) continue;
    const std::string path = line.substr(slash);
    const std::string file = std::filesystem::path(path).filename().string();
    if (file.find("blas") == std::string::npos) continue;
    std::error_code ec;
    const auto real = std::filesystem::canonical(path, ec);
    info.library = ec ? path : real.string();
    if (info.library.find("openblas") != std::string::npos) {
      info.openblas = true;
      break;
    }
    if (info.library.find("/blas/") != std::string::npos) info.reference = true;
  }
  return info;
}

}  // namespace curio::train
