// Build-time helper: writes the synthetic model the generated-header test compiles against.
// Usage: curio_nn_make_synthetic_model DIR NAME SEED
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "tests/nn/synthetic_model.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s DIR NAME SEED\n", argv[0]);
    return 2;
  }
  try {
    curio::nn::testing::write_synthetic_model(argv[1], argv[2],
                                              std::strtoull(argv[3], nullptr, 10));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
