// Cortex-M7 (QEMU mps2-an500) run of the int8 kernels on vectors computed by the host's
// reference kernels: every output must match bit for bit.
#include <cstdint>

#include "tests/nn/qemu/kernel_vectors.hpp"
#include "firmware/nn/conv_s8.hpp"
#include "firmware/nn/fully_connected_s8.hpp"
#include "toolchain/qemu/semihosting.h"

namespace {

using namespace curio::nn;

alignas(16) int8_t g_scratch[48 * 1024];  // the row band of a 32-channel 4×4 conv: its int16 filter alone is 32 KiB
alignas(16) int8_t g_out_s8[4096];
alignas(16) int32_t g_out_s32[1024];

template <typename T>
bool same(const char* name, const T* got, const T* want, int32_t n) {
  for (int32_t i = 0; i < n; ++i) {
    if (got[i] != want[i]) {
      curio_semihost_print("FAIL ");
      curio_semihost_print(name);
      curio_semihost_print(": first mismatch at index ");
      curio_semihost_print_u32(static_cast<uint32_t>(i));
      curio_semihost_print(" got ");
      curio_semihost_print_hex32(static_cast<uint32_t>(got[i]));
      curio_semihost_print(" want ");
      curio_semihost_print_hex32(static_cast<uint32_t>(want[i]));
      curio_semihost_print("\n");
      return false;
    }
  }
  curio_semihost_print("ok   ");
  curio_semihost_print(name);
  curio_semihost_print("\n");
  return true;
}

bool fits(const char* name, int32_t scratch, int32_t outputs) {
  if (scratch <= static_cast<int32_t>(sizeof g_scratch) && outputs <= 1024) return true;
  curio_semihost_print("FAIL ");
  curio_semihost_print(name);
  curio_semihost_print(": buffers too small for this vector\n");
  return false;
}

}  // namespace

int main() {
  int failures = 0;
  for (const auto& v : qemu_vectors::kConvVectors) {
    const int32_t need = conv_s8_get_buffer_size(v.params, v.input_dims, v.filter_dims);
    if (!fits(v.name, need, v.expected_size)) {
      ++failures;
      continue;
    }
    const Status s = conv_s8({g_scratch, need}, v.params, {v.multiplier, v.shift}, v.input_dims,
                             v.input, v.filter_dims, v.filter, v.bias, v.output_dims, g_out_s8);
    if (s != Status::kOk || !same(v.name, g_out_s8, v.expected, v.expected_size)) ++failures;
  }
  for (const auto& v : qemu_vectors::kFcVectors) {
    const int32_t need = fully_connected_s8_get_buffer_size(v.dims);
    if (!fits(v.name, need, v.expected_size)) {
      ++failures;
      continue;
    }
    Status s;
    bool ok;
    if (v.filter_w16 != nullptr) {
      s = fully_connected_s8_w16_s32({g_scratch, need}, v.params.input_offset, v.dims, v.input,
                                     v.filter_w16, v.bias, g_out_s32);
      ok = same(v.name, g_out_s32, v.expected_s32, v.expected_size);
    } else if (v.s32) {
      s = fully_connected_s8_s32({g_scratch, need}, v.params.input_offset, v.dims, v.input,
                                 v.filter, v.bias, g_out_s32);
      ok = same(v.name, g_out_s32, v.expected_s32, v.expected_size);
    } else {
      s = fully_connected_s8({g_scratch, need}, v.params, {v.multiplier, v.shift}, v.dims, v.input,
                             v.filter, v.bias, g_out_s8);
      ok = same(v.name, g_out_s8, v.expected_s8, v.expected_size);
    }
    if (s != Status::kOk || !ok) ++failures;
  }
  curio_semihost_print(failures == 0 ? "PASS\n" : "FAILED\n");
  return failures == 0 ? 0 : 1;
}
