// 2-D convolution, int8 in and out, per-output-channel requantization (CMSIS-NN's
// arm_convolve_s8): input NHWC, filter [C_out, H, W, C_in], int32 bias per output channel,
// padded inputs equal the input zero point (they contribute nothing).
#pragma once
#include <cstdint>

#include "firmware/nn/dot_block.hpp"
#include "firmware/nn/nn_types.hpp"
#include "firmware/nn/status.hpp"

namespace curio::nn {

// How conv_s8 computes its sums, and where it puts things in its scratch.
//  - dot path (portable): 2 pixels × 4 channels at a time, dot products over im2col
//    columns (int16, input offset added, window zero-padded to kDepthGranule); the filter
//    is copied with that padding only if padding was needed. Scratch: columns, the two
//    pixels' int32 sums, the filter copy.
//  - channel-vector path (host AVX-512 VNNI build, C_out % 16 == 0, window rows a multiple
//    of 4 bytes): 8 pixels × 16 channels per vector, straight from the whole input stored
//    as x + 128 in a border of zero-point bytes. Scratch: that image, the sums, the filter
//    in 4-byte groups and one int32 correction per channel.
struct ConvScratchLayout {
  bool channel_vector;
  int32_t depth;      // filter window length h·w·C_in
  int32_t col_depth;  // dot path: padded window length (stride between columns)
  int32_t cols;       // pixels per block
  int32_t image_w;    // channel-vector path: padded image width, height
  int32_t image_h;
  int32_t sums_offset;  // bytes from the start of the scratch
  int32_t filter_offset;
  bool filter_copied;
  int32_t bytes;
};

inline constexpr int32_t kChannelVectorMaxDepth = 2048;  // bounds the filter copy

// Shapes the channel-vector path can take (it is used when also compiled in).
constexpr bool conv_s8_channel_vector_shape(const Dims& input_dims, const Dims& filter_dims) {
  return filter_dims.n % 16 == 0 && (filter_dims.w * input_dims.c) % 4 == 0 &&
         filter_dims.h * filter_dims.w * input_dims.c <= kChannelVectorMaxDepth;
}

constexpr ConvScratchLayout conv_s8_scratch_layout(const Dims& input_dims, const Dims& filter_dims,
                                                   const Tile& padding, bool channel_vector) {
  ConvScratchLayout l{};
  l.depth = filter_dims.h * filter_dims.w * input_dims.c;
  const int32_t c_out = filter_dims.n;
  const auto i16 = static_cast<int32_t>(sizeof(int16_t));
  const auto i32 = static_cast<int32_t>(sizeof(int32_t));
  l.channel_vector = channel_vector;
  l.cols = channel_vector ? 8 : 2;
  int32_t first_bytes = 0;
  if (channel_vector) {
    l.col_depth = l.depth;
    l.image_w = input_dims.w + 2 * padding.w;
    l.image_h = input_dims.h + 2 * padding.h;
    first_bytes = l.image_h * l.image_w * input_dims.c;
  } else {
    l.col_depth = detail::round_up(l.depth, detail::kDepthGranule);
    first_bytes = l.cols * l.col_depth * i16;
  }
  l.sums_offset = detail::round_up(first_bytes, 16);
  l.filter_offset = l.sums_offset + detail::round_up(l.cols * c_out * i32, 16);
  l.filter_copied = channel_vector || l.col_depth != l.depth;
  const int32_t filter_bytes =
      channel_vector ? detail::round_up(c_out * l.depth, 16) + c_out * i32 : c_out * l.col_depth;
  l.bytes = l.filter_offset + (l.filter_copied ? detail::round_up(filter_bytes, 16) : 0);
  return l;
}

// The Cortex-M DSP path's row band (CURIO_NN_ARM_DSP): the filter widened to int16 once per
// call (two rows interleaved per group of four values), and each input row a window reads
// widened once (x + input_offset, int16, the padding as zeros) into one of f.h row slots, so
// a window row is f.w·C_in contiguous int16 values in its slot and no im2col column is built.
// Shapes: window rows a multiple of 4 values (groups never straddle rows), stride.w·C_in even
// (every window starts on a word), at most kBandMaxRows filter rows. Scratch: the widened
// filter, the slots, two pixels' windows copied out of the slots as contiguous columns, their
// int32 sums and four int32 requantization constants per output channel.
inline constexpr int32_t kBandMaxRows = 8;
struct ConvBandLayout {
  bool usable;
  int32_t slot_values;  // int16 values per row slot (a multiple of 4)
  int32_t ring_offset;  // bytes from the start of the scratch
  int32_t cols_offset;
  int32_t sums_offset;
  int32_t requant_offset;
  int32_t bytes;
};
constexpr ConvBandLayout conv_s8_band_layout(const Dims& input_dims, const Dims& filter_dims,
                                             const ConvParams& params) {
  ConvBandLayout l{};
  l.usable = (filter_dims.w * input_dims.c) % 4 == 0 && (params.stride.w * input_dims.c) % 2 == 0 &&
             filter_dims.h <= kBandMaxRows;
  if (!l.usable) return l;
  const auto i16 = static_cast<int32_t>(sizeof(int16_t));
  const auto i32 = static_cast<int32_t>(sizeof(int32_t));
  const int32_t depth = filter_dims.h * filter_dims.w * input_dims.c;
  l.slot_values = detail::round_up((input_dims.w + 2 * params.padding.w) * input_dims.c, 4);
  l.ring_offset = detail::round_up(filter_dims.n * depth * i16, 16);
  l.cols_offset = l.ring_offset + detail::round_up(filter_dims.h * l.slot_values * i16, 16);
  l.sums_offset = l.cols_offset + detail::round_up(2 * depth * i16, 16);
  l.requant_offset = l.sums_offset + detail::round_up(2 * filter_dims.n * i32, 16);
  l.bytes = l.requant_offset + 4 * filter_dims.n * i32;
  return l;
}

// Scratch bytes conv_s8 needs in ctx. On hosts this covers every path (the host tests also
// build the Cortex-M one), so the size does not depend on the caller's compile flags.
constexpr int32_t conv_s8_get_buffer_size(const ConvParams& params, const Dims& input_dims,
                                          const Dims& filter_dims) {
  const Tile& pad = params.padding;
  const int32_t dot = conv_s8_scratch_layout(input_dims, filter_dims, pad, false).bytes;
  const int32_t vec = detail::kHostTarget && conv_s8_channel_vector_shape(input_dims, filter_dims)
                          ? conv_s8_scratch_layout(input_dims, filter_dims, pad, true).bytes
                          : 0;
  const int32_t band = conv_s8_band_layout(input_dims, filter_dims, params).bytes;
  const int32_t most = dot > vec ? dot : vec;
  return most > band ? most : band;
}

// A prepared filter: the channel-vector path re-lays the filter (4-byte groups per channel
// plus one int32 correction per channel) in its scratch on every call, unless the caller
// prepared it once (conv_s8_prepare) and passes it to conv_s8: the Encoder does, for its
// four convs. Bytes it needs: 0 where no compiled path uses one (Cortex-M; shapes the
// channel-vector path does not take), so a caller can size its storage at compile time.
constexpr int32_t conv_s8_prepared_bytes(const Dims& input_dims, const Dims& filter_dims) {
  if (!detail::kHostTarget || !conv_s8_channel_vector_shape(input_dims, filter_dims)) return 0;
  const int32_t depth = filter_dims.h * filter_dims.w * input_dims.c;
  return detail::round_up(filter_dims.n * depth, 16) + filter_dims.n * static_cast<int32_t>(sizeof(int32_t));
}

// Writes the prepared filter of (params.input_offset, filter) into `prepared`
// (conv_s8_prepared_bytes bytes, 16-byte aligned). Nothing to do (kOk) where that size is 0
// or where this build has no channel-vector path; the result is only valid for this build.
Status conv_s8_prepare(const ConvParams& params, const Dims& input_dims, const Dims& filter_dims,
                       const int8_t* filter, int8_t* prepared);

// The inner-loop path the library was built with: "portable", "avx512-vnni" or "arm-dsp".
const char* simd_path();

// output[b,y,x,co] = clamp(zp_out + rescale_co(bias[co] + Σ (in + input_offset)·filter))
// where in runs over the filter window at (y·stride − pad, x·stride − pad). bias may be
// nullptr (zero). output_dims must be {n, (h + 2·pad − kh)/stride + 1, …, C_out}.
// `prepared`: nullptr, or conv_s8_prepare's output for these params and filter (the sums are
// the same integers either way).
Status conv_s8(const Context& ctx, const ConvParams& params, const PerChannelQuantParams& quant,
               const Dims& input_dims, const int8_t* input, const Dims& filter_dims,
               const int8_t* filter, const int32_t* bias, const Dims& output_dims, int8_t* output,
               const int8_t* prepared = nullptr);

}  // namespace curio::nn
