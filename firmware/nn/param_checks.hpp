// Argument checks shared by the kernels; each returns the Status the kernel reports.
#pragma once
#include <cstdint>

#include "firmware/nn/nn_types.hpp"
#include "firmware/nn/status.hpp"

namespace curio::nn::detail {

// −(zero point) of an int8 tensor; x + offset must stay within int16 and ±255.
constexpr bool valid_input_offset(int32_t offset) {
  return offset >= -127 && offset <= 128;
}
constexpr bool valid_output_offset(int32_t offset) {
  return offset >= -128 && offset <= 127;
}

// Longest dot product whose int32 sum cannot overflow: 65,535 · 255 · 128 < 2^31.
inline constexpr int32_t kMaxDepth = 65535;
// The same for int16 weights limited to ±16,383: 514 · 255 · 16,383 < 2^31.
inline constexpr int32_t kMaxDepthWide = 514;
inline constexpr int32_t kMaxWideWeight = 16383;

constexpr bool valid_activation(const Activation& a) {
  return a.min >= -128 && a.max <= 127 && a.min <= a.max;
}

inline Status check_scratch(const Context& ctx, int32_t needed) {
  if (needed > 0 && ctx.buf == nullptr) return Status::kArgumentError;
  if (reinterpret_cast<uintptr_t>(ctx.buf) % kScratchAlignment != 0) {
    return Status::kArgumentError;
  }
  return ctx.size < needed ? Status::kBufferTooSmall : Status::kOk;
}

inline bool valid_quant(const PerChannelQuantParams& q, int32_t channels) {
  if (q.multiplier == nullptr || q.shift == nullptr) return false;
  for (int32_t c = 0; c < channels; ++c) {
    if (q.multiplier[c] < 0 || q.shift[c] < -31 || q.shift[c] > 30) return false;
  }
  return true;
}

}  // namespace curio::nn::detail
