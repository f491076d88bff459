// Writes tests/nn/qemu/encoder_layer_hashes.hpp. Usage: curio_nn_make_encoder_layer_hashes OUT.hpp
#include <cstdio>
#include <fstream>

#include "tests/nn/encoder_layer_reference.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s tests/nn/qemu/encoder_layer_hashes.hpp\n", argv[0]);
    return 2;
  }
  std::ofstream out(argv[1], std::ios::binary | std::ios::trunc);
  out << curio::nn::testing::make_encoder_layer_hashes_header();
  out.close();
  if (!out) {
    std::fprintf(stderr, "error: cannot write %s\n", argv[1]);
    return 1;
  }
  return 0;
}
