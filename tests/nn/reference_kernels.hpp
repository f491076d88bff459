// Plain, obviously-correct integer references for the int8 kernels: exact int64 sums,
// requantization written from its definition (floor divisions), no blocking, no im2col.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "firmware/nn/nn_types.hpp"

namespace curio::nn::ref {

// floor(a / b) for b > 0.
inline int64_t floor_div(int64_t a, int64_t b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

inline int32_t clamp32(int64_t v) {
  return static_cast<int32_t>(std::clamp<int64_t>(v, INT32_MIN, INT32_MAX));
}

// a·b/2^31, ties upward (gemmlowp), INT32_MIN² → INT32_MAX.
inline int32_t srdhm(int32_t a, int32_t b) {
  const int64_t p = static_cast<int64_t>(a) * b;
  return clamp32(floor_div(p + (int64_t{1} << 30), int64_t{1} << 31));
}

// x/2^e rounded half away from zero.
inline int32_t rdbp(int32_t x, int e) {
  const int64_t m = std::abs(static_cast<int64_t>(x));
  const int64_t q = e == 0 ? m : (m + (int64_t{1} << (e - 1))) >> e;
  return static_cast<int32_t>(x < 0 ? -q : q);
}

inline int32_t mbqm(int32_t x, int32_t mult, int shift) {
  const int32_t left = shift > 0 ? clamp32(static_cast<int64_t>(x) << shift) : x;
  return rdbp(srdhm(left, mult), shift > 0 ? 0 : -shift);
}

inline int8_t requant(int64_t acc, int32_t mult, int shift, int32_t out_off, Activation act) {
  const int64_t v = static_cast<int64_t>(mbqm(clamp32(acc), mult, shift)) + out_off;
  return static_cast<int8_t>(std::clamp<int64_t>(v, act.min, act.max));
}

inline std::vector<int8_t> conv(const ConvParams& p, const std::vector<int32_t>& mult,
                                const std::vector<int32_t>& shift, const Dims& in,
                                const std::vector<int8_t>& input, const Dims& f,
                                const std::vector<int8_t>& filter, const std::vector<int32_t>& bias,
                                const Dims& out) {
  std::vector<int8_t> result(static_cast<size_t>(out.n * out.h * out.w * out.c));
  for (int b = 0; b < out.n; ++b)
    for (int oy = 0; oy < out.h; ++oy)
      for (int ox = 0; ox < out.w; ++ox)
        for (int co = 0; co < out.c; ++co) {
          int64_t acc = bias.empty() ? 0 : bias[static_cast<size_t>(co)];
          for (int ky = 0; ky < f.h; ++ky)
            for (int kx = 0; kx < f.w; ++kx)
              for (int ci = 0; ci < in.c; ++ci) {
                const int iy = oy * p.stride.h - p.padding.h + ky;
                const int ix = ox * p.stride.w - p.padding.w + kx;
                if (iy < 0 || iy >= in.h || ix < 0 || ix >= in.w) continue;  // zero point
                const int64_t x =
                    input[static_cast<size_t>(((b * in.h + iy) * in.w + ix) * in.c + ci)];
                const int64_t w =
                    filter[static_cast<size_t>(((co * f.h + ky) * f.w + kx) * f.c + ci)];
                acc += (x + p.input_offset) * w;
              }
          result[static_cast<size_t>(((b * out.h + oy) * out.w + ox) * out.c + co)] =
              requant(acc, mult[static_cast<size_t>(co)], shift[static_cast<size_t>(co)],
                      p.output_offset, p.activation);
        }
  return result;
}

template <typename Weight>
inline std::vector<int64_t> fc_acc(int32_t input_offset, const FcDims& d,
                                   const std::vector<int8_t>& input,
                                   const std::vector<Weight>& filter,
                                   const std::vector<int32_t>& bias) {
  std::vector<int64_t> acc(static_cast<size_t>(d.batches * d.output_depth));
  for (int b = 0; b < d.batches; ++b)
    for (int o = 0; o < d.output_depth; ++o) {
      int64_t s = bias.empty() ? 0 : bias[static_cast<size_t>(o)];
      for (int i = 0; i < d.input_depth; ++i) {
        s += (int64_t{input[static_cast<size_t>(b * d.input_depth + i)]} + input_offset) *
             filter[static_cast<size_t>(o * d.input_depth + i)];
      }
      acc[static_cast<size_t>(b * d.output_depth + o)] = s;
    }
  return acc;
}

// Exact comparison that names the first mismatch.
template <typename T>
::testing::AssertionResult same_values(const T* got, const std::vector<T>& want) {
  for (size_t i = 0; i < want.size(); ++i) {
    if (got[i] != want[i]) {
      return ::testing::AssertionFailure()
             << "first mismatch at index " << i << ": got " << static_cast<int64_t>(got[i])
             << ", want " << static_cast<int64_t>(want[i]) << " (of " << want.size() << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace curio::nn::ref
