// conv_s8 and fully_connected_s8 bit-exact against the plain references on random data,
// over the encoder's shapes and awkward ones (odd widths, channel remainders, batches).
#include <gtest/gtest.h>

#include <vector>

#include "firmware/explore/prng.hpp"
#include "firmware/nn/conv_s8.hpp"
#include "firmware/nn/fully_connected_s8.hpp"
#include "firmware/nn/quantize_multiplier.hpp"
#include "tests/nn/reference_kernels.hpp"

namespace curio::nn {
namespace {

std::vector<int8_t> random_s8(Prng& rng, size_t n, int lo = -128, int hi = 127) {
  std::vector<int8_t> v(n);
  for (auto& x : v)
    x = static_cast<int8_t>(lo + static_cast<int>(rng.below(static_cast<uint32_t>(hi - lo + 1))));
  return v;
}

// Per-channel rescales around `typical` (what real layers have: 1e-4 .. 1e-1).
void random_quant(Prng& rng, int channels, double typical, std::vector<int32_t>* mult,
                  std::vector<int32_t>* shift) {
  for (int c = 0; c < channels; ++c) {
    QuantizedMultiplier m;
    ASSERT_EQ(quantize_multiplier(typical * rng.uniform(0.25, 4.0), &m), Status::kOk);
    mult->push_back(m.multiplier);
    shift->push_back(m.shift);
  }
}

// Scratch with the alignment the kernels require.
struct Scratch {
  explicit Scratch(int32_t bytes) : words(static_cast<size_t>(bytes / 16 + 1)) {}
  Context ctx() { return {words.data(), static_cast<int32_t>(words.size() * 16)}; }
  struct alignas(16) Block {
    char b[16];
  };
  std::vector<Block> words;
};

struct ConvCase {
  Dims in;
  Dims filter;  // {c_out, kh, kw, c_in}
  Tile stride, pad;
  int batches;
};

void run_conv_case(const ConvCase& cc, uint64_t seed, double rescale_factor = 1.0) {
  Prng rng(seed);
  Dims in = cc.in;
  in.n = cc.batches;
  const Dims f = cc.filter;
  const Dims out{in.n, (in.h + 2 * cc.pad.h - f.h) / cc.stride.h + 1,
                 (in.w + 2 * cc.pad.w - f.w) / cc.stride.w + 1, f.n};
  ConvParams p;
  p.input_offset = static_cast<int32_t>(rng.below(256)) - 127;
  // Zero point in the lower half so the clamp [zp − 3, ~127] leaves many values.
  p.output_offset = static_cast<int32_t>(rng.below(129)) - 128;
  p.stride = cc.stride;
  p.padding = cc.pad;
  p.activation = {std::max(-128, p.output_offset - 3), 127 - static_cast<int32_t>(rng.below(3))};
  const auto input = random_s8(rng, static_cast<size_t>(in.n * in.h * in.w * in.c));
  const auto filter = random_s8(rng, static_cast<size_t>(f.n * f.h * f.w * f.c), -127, 127);
  // Bias of the same size as the sums, so neither hides the other.
  const auto bias_span = static_cast<uint32_t>(64.0 * 128.0 * std::sqrt(f.h * f.w * f.c));
  std::vector<int32_t> bias(static_cast<size_t>(f.n));
  for (auto& b : bias) b = static_cast<int32_t>(rng.below(2 * bias_span + 1) - bias_span);
  std::vector<int32_t> mult, shift;
  // Sums reach ~128·128·depth; scale so outputs span the int8 range.
  random_quant(rng, f.n, rescale_factor * 2.0 / (128.0 * std::sqrt(f.h * f.w * f.c)), &mult,
               &shift);

  Scratch scratch(conv_s8_get_buffer_size(p, in, f));
  std::vector<int8_t> got(static_cast<size_t>(out.n * out.h * out.w * out.c), 99);
  ASSERT_EQ(conv_s8(scratch.ctx(), p, {mult.data(), shift.data()}, in, input.data(), f,
                    filter.data(), bias.data(), out, got.data()),
            Status::kOk);
  const auto want = ref::conv(p, mult, shift, in, input, f, filter, bias, out);
  EXPECT_TRUE(ref::same_values(got.data(), want));
  // With the filter prepared once (conv_s8_prepare), as the Encoder runs it: the same integers.
  std::vector<int8_t> prepared(static_cast<size_t>(conv_s8_prepared_bytes(in, f)) + 64);
  auto* const aligned = reinterpret_cast<int8_t*>((reinterpret_cast<uintptr_t>(prepared.data()) + 63) & ~uintptr_t{63});
  ASSERT_EQ(conv_s8_prepare(p, in, f, filter.data(), aligned), Status::kOk);
  std::vector<int8_t> got_prepared(got.size(), 99);
  ASSERT_EQ(conv_s8(scratch.ctx(), p, {mult.data(), shift.data()}, in, input.data(), f, filter.data(),
                    bias.data(), out, got_prepared.data(), aligned),
            Status::kOk);
  EXPECT_EQ(got_prepared, got);
  if (rescale_factor > 1.0) return;  // large rescales saturate most outputs on purpose
  // Outputs must not all sit at one clamp edge, or the test proves little.
  int distinct = 0;
  for (int v = -128; v <= 127; ++v) distinct += std::count(want.begin(), want.end(), v) > 0;
  EXPECT_GE(distinct, std::min<int>(20, static_cast<int>(want.size()) / 4));
}

TEST(ConvS8, EncoderShapesBitExact) {
  const Tile s2{2, 2}, p1{1, 1};
  run_conv_case({{1, 64, 64, 3}, {32, 4, 4, 3}, s2, p1, 1}, 1);
  run_conv_case({{1, 32, 32, 32}, {32, 4, 4, 32}, s2, p1, 1}, 2);
  run_conv_case({{1, 16, 16, 32}, {32, 4, 4, 32}, s2, p1, 1}, 3);
  run_conv_case({{1, 8, 8, 32}, {32, 4, 4, 32}, s2, p1, 1}, 4);
}

TEST(ConvS8, AwkwardShapesBitExact) {
  uint64_t seed = 100;
  for (const ConvCase& cc : std::vector<ConvCase>{
           {{1, 7, 5, 3}, {5, 3, 3, 3}, {1, 1}, {1, 1}, 2},    // odd width, 5 channels
           {{1, 9, 9, 1}, {3, 4, 4, 1}, {2, 2}, {1, 1}, 1},    // odd size, stride 2
           {{1, 6, 11, 7}, {6, 2, 3, 7}, {1, 2}, {0, 1}, 3},   // unequal strides/pads
           {{1, 5, 5, 16}, {9, 1, 1, 16}, {1, 1}, {0, 0}, 1},  // 1×1
           {{1, 3, 3, 2}, {4, 3, 3, 2}, {1, 1}, {0, 0}, 1},    // single output pixel
           {{1, 4, 4, 2}, {1, 5, 5, 2}, {3, 3}, {2, 2}, 1},    // pad beyond the image
           // Cortex-M row band (window rows of 4·k values): rows reused at stride 1, odd
           // width and channel count, two images; rows padded beyond the image.
           {{1, 9, 9, 2}, {5, 3, 2, 2}, {1, 2}, {1, 1}, 2},
           {{1, 6, 5, 4}, {3, 5, 1, 4}, {2, 1}, {2, 0}, 1},
       }) {
    SCOPED_TRACE(seed);
    run_conv_case(cc, seed++);
  }
}

// Rescales ≥ 0.5 and left shifts take the general requantization form.
TEST(ConvS8, LargeRescalesBitExact) {
  run_conv_case({{1, 16, 16, 32}, {32, 4, 4, 32}, {2, 2}, {1, 1}, 1}, 31, 3000.0);
  run_conv_case({{1, 7, 5, 3}, {5, 3, 3, 3}, {1, 1}, {1, 1}, 2}, 32, 3000.0);
  run_conv_case({{1, 64, 64, 3}, {32, 4, 4, 3}, {2, 2}, {1, 1}, 1}, 33, 3000.0);
}

TEST(ConvS8, RejectsBadArguments) {
  const Dims in{1, 8, 8, 4}, f{4, 3, 3, 4}, out{1, 8, 8, 4};
  std::vector<int8_t> input(256), filter(144), output(256);
  std::vector<int32_t> mult(4, 1 << 30), shift(4, 0);
  ConvParams p;
  p.padding = {1, 1};
  Scratch scratch(conv_s8_get_buffer_size(p, in, f));
  const PerChannelQuantParams q{mult.data(), shift.data()};
  EXPECT_EQ(
      conv_s8(scratch.ctx(), p, q, in, input.data(), f, filter.data(), nullptr, out, output.data()),
      Status::kOk);
  Context small = scratch.ctx();
  small.size = conv_s8_get_buffer_size(p, in, f) - 1;
  EXPECT_EQ(conv_s8(small, p, q, in, input.data(), f, filter.data(), nullptr, out, output.data()),
            Status::kBufferTooSmall);
  Context misaligned = scratch.ctx();
  misaligned.buf = static_cast<char*>(misaligned.buf) + 2;
  EXPECT_EQ(
      conv_s8(misaligned, p, q, in, input.data(), f, filter.data(), nullptr, out, output.data()),
      Status::kArgumentError);
  EXPECT_EQ(conv_s8(scratch.ctx(), p, q, in, input.data(), f, filter.data(), nullptr,
                    Dims{1, 7, 8, 4}, output.data()),
            Status::kArgumentError);
  EXPECT_EQ(
      conv_s8(scratch.ctx(), p, q, in, nullptr, f, filter.data(), nullptr, out, output.data()),
      Status::kArgumentError);
  shift[2] = 31;
  EXPECT_EQ(
      conv_s8(scratch.ctx(), p, q, in, input.data(), f, filter.data(), nullptr, out, output.data()),
      Status::kArgumentError);
}

void run_fc_case(FcDims d, uint64_t seed) {
  Prng rng(seed);
  FcParams p;
  p.input_offset = static_cast<int32_t>(rng.below(256)) - 127;
  p.output_offset = static_cast<int32_t>(rng.below(256)) - 128;
  p.activation = {p.output_offset, 127};
  const auto input = random_s8(rng, static_cast<size_t>(d.batches * d.input_depth));
  const auto filter =
      random_s8(rng, static_cast<size_t>(d.output_depth * d.input_depth), -127, 127);
  const auto bias_span = static_cast<uint32_t>(64.0 * 128.0 * std::sqrt(d.input_depth));
  std::vector<int32_t> bias(static_cast<size_t>(d.output_depth));
  for (auto& b : bias) b = static_cast<int32_t>(rng.below(2 * bias_span + 1) - bias_span);
  std::vector<int32_t> mult, shift;
  random_quant(rng, d.output_depth, 2.0 / (128.0 * std::sqrt(d.input_depth)), &mult, &shift);
  Scratch scratch(fully_connected_s8_get_buffer_size(d));

  const auto acc = ref::fc_acc(p.input_offset, d, input, filter, bias);
  std::vector<int8_t> want(acc.size());
  std::vector<int32_t> want32(acc.size());
  for (size_t i = 0; i < acc.size(); ++i) {
    const auto o = static_cast<size_t>(static_cast<int32_t>(i) % d.output_depth);
    want[i] = ref::requant(acc[i], mult[o], shift[o], p.output_offset, p.activation);
    want32[i] = ref::clamp32(acc[i]);
  }
  std::vector<int8_t> got(acc.size(), 99);
  ASSERT_EQ(fully_connected_s8(scratch.ctx(), p, {mult.data(), shift.data()}, d, input.data(),
                               filter.data(), bias.data(), got.data()),
            Status::kOk);
  EXPECT_TRUE(ref::same_values(got.data(), want));
  std::vector<int32_t> got32(acc.size(), 99);
  ASSERT_EQ(fully_connected_s8_s32(scratch.ctx(), p.input_offset, d, input.data(), filter.data(),
                                   bias.data(), got32.data()),
            Status::kOk);
  EXPECT_TRUE(ref::same_values(got32.data(), want32));

  // int16 weights at their full ±16,383 range (the latent layer's kernel).
  if (d.input_depth > 514) return;
  std::vector<int16_t> wide(filter.size());
  for (auto& w : wide) w = static_cast<int16_t>(static_cast<int32_t>(rng.below(32767)) - 16383);
  wide[0] = 16383;
  wide[1] = -16383;
  const auto acc_wide = ref::fc_acc(p.input_offset, d, input, wide, bias);
  std::vector<int32_t> want_wide(acc_wide.size());
  for (size_t i = 0; i < acc_wide.size(); ++i) want_wide[i] = ref::clamp32(acc_wide[i]);
  ASSERT_EQ(fully_connected_s8_w16_s32(scratch.ctx(), p.input_offset, d, input.data(), wide.data(),
                                       bias.data(), got32.data()),
            Status::kOk);
  EXPECT_TRUE(ref::same_values(got32.data(), want_wide));
}

TEST(FullyConnectedS8, WideWeightsRejectTooDeepInputs) {
  const FcDims d{1, 515, 1};
  std::vector<int8_t> input(515);
  std::vector<int16_t> filter(515);
  int32_t out = 0;
  Scratch scratch(fully_connected_s8_get_buffer_size(d));
  EXPECT_EQ(
      fully_connected_s8_w16_s32(scratch.ctx(), 0, d, input.data(), filter.data(), nullptr, &out),
      Status::kArgumentError);
}

TEST(FullyConnectedS8, EncoderShapesBitExact) {
  run_fc_case({1, 512, 256}, 11);
  run_fc_case({1, 256, 256}, 12);
  run_fc_case({1, 256, 20}, 13);
}

TEST(FullyConnectedS8, AwkwardShapesBitExact) {
  run_fc_case({3, 37, 7}, 21);
  run_fc_case({1, 1, 1}, 22);
  run_fc_case({2, 5, 13}, 23);
}

TEST(FullyConnectedS8, RejectsBadArguments) {
  const FcDims d{1, 8, 4};
  std::vector<int8_t> input(8), filter(32), output(4);
  std::vector<int32_t> out32(4), mult(4, 1 << 30), shift(4, 0);
  Scratch scratch(fully_connected_s8_get_buffer_size(d));
  FcParams p;
  EXPECT_EQ(fully_connected_s8(scratch.ctx(), p, {mult.data(), shift.data()}, d, input.data(),
                               filter.data(), nullptr, output.data()),
            Status::kOk);
  Context small = scratch.ctx();
  small.size = 15;
  EXPECT_EQ(fully_connected_s8_s32(small, 0, d, input.data(), filter.data(), nullptr, out32.data()),
            Status::kBufferTooSmall);
  p.input_offset = 129;
  EXPECT_EQ(fully_connected_s8(scratch.ctx(), p, {mult.data(), shift.data()}, d, input.data(),
                               filter.data(), nullptr, output.data()),
            Status::kArgumentError);
  p.input_offset = 0;
  p.activation = {5, 4};
  EXPECT_EQ(fully_connected_s8(scratch.ctx(), p, {mult.data(), shift.data()}, d, input.data(),
                               filter.data(), nullptr, output.data()),
            Status::kArgumentError);
  EXPECT_EQ(fully_connected_s8(scratch.ctx(), FcParams{}, {nullptr, shift.data()}, d, input.data(),
                               filter.data(), nullptr, output.data()),
            Status::kArgumentError);
}

#ifdef CURIO_NN_EXPECTED_PATH
// The library under test took the inner-loop path its build asked for (so the bit-exact
// tests above checked that path, not a fallback).
TEST(SimdPath, IsTheOneThisBuildAskedFor) {
  EXPECT_STREQ(simd_path(), CURIO_NN_EXPECTED_PATH);
}
#endif

}  // namespace
}  // namespace curio::nn
