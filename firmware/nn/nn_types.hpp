// Plain structs the int8 kernels take (CMSIS-NN style): dims, layer parameters,
// quantization parameters and the caller-owned scratch buffer.
#pragma once
#include <cstdint>

namespace curio::nn {

// A 4-D tensor shape. Activations are NHWC; conv filters are [C_out, H, W, C_in]
// stored as {n = C_out, h, w, c = C_in}.
struct Dims {
  int32_t n = 1;
  int32_t h = 1;
  int32_t w = 1;
  int32_t c = 1;
};

struct Tile {
  int32_t h = 0;
  int32_t w = 0;
};

// Clamp of the int8 output; a fused ReLU is {output zero point, 127}.
struct Activation {
  int32_t min = -128;
  int32_t max = 127;
};

struct ConvParams {
  int32_t input_offset = 0;   // −(input zero point), added to every input value
  int32_t output_offset = 0;  // +(output zero point)
  Tile stride{1, 1};
  Tile padding{0, 0};  // same on both sides; padded inputs are the zero point
  Activation activation{};
};

struct FcParams {
  int32_t input_offset = 0;   // −(input zero point)
  int32_t output_offset = 0;  // +(output zero point)
  Activation activation{};
};

// One rescale per output channel: real = s_in·s_w[c]/s_out = multiplier[c]·2^(shift[c]−31).
struct PerChannelQuantParams {
  const int32_t* multiplier = nullptr;
  const int32_t* shift = nullptr;
};

// Fully connected shapes: filter is [output_depth, input_depth] row-major.
struct FcDims {
  int32_t batches = 1;
  int32_t input_depth = 0;
  int32_t output_depth = 0;
};

// Scratch memory the caller owns; size from the kernel's *_get_buffer_size(). Must be
// aligned to kScratchAlignment.
struct Context {
  void* buf = nullptr;
  int32_t size = 0;
};

inline constexpr int32_t kScratchAlignment = 16;

}  // namespace curio::nn
