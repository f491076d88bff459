// Kernel test vectors for the Cortex-M run (tests/nn/qemu/): random inputs and the
// outputs the plain reference kernels compute for them on the host, as a C++ header.
#pragma once
#include <string>

namespace curio::nn::testing {

// The full text of tests/nn/qemu/kernel_vectors.hpp, deterministic.
std::string make_qemu_vectors_header();

inline constexpr const char* kQemuVectorsPath = "tests/nn/qemu/kernel_vectors.hpp";

}  // namespace curio::nn::testing
