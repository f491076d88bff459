// Float scale → Q31 multiplier + shift (TFLite's QuantizeMultiplier). Run by the host quantizer;
// kept beside fixed_point.hpp so both sides agree on what a (multiplier, shift) pair means:
// real = multiplier · 2^(shift − 31).
#pragma once
#include <cmath>
#include <cstdint>

#include "firmware/nn/status.hpp"

namespace curio::nn {

struct QuantizedMultiplier {
  int32_t multiplier = 0;  // Q31 mantissa in [2^30, 2^31 − 1], or 0 for a zero scale
  int32_t shift = 0;       // −31..30, positive = left
};

// frexp, mantissa·2^31 rounded half away from zero, a mantissa that rounds to 2^31 is
// halved and the exponent incremented. Scales below 2^−32 become (0, 0) (they rescale every
// int32 accumulator to ±1 at most). Negative, non-finite or too-large (≥ 2^30) scales:
// kOutOfRange / kArgumentError, *out untouched.
inline Status quantize_multiplier(double real, QuantizedMultiplier* out) {
  if (out == nullptr || !std::isfinite(real) || real < 0.0) return Status::kArgumentError;
  if (real == 0.0) {
    *out = {0, 0};
    return Status::kOk;
  }
  int exponent = 0;
  const double mantissa = std::frexp(real, &exponent);  // in [0.5, 1)
  auto q = static_cast<int64_t>(std::llround(mantissa * 2147483648.0));
  if (q == (int64_t{1} << 31)) {
    q /= 2;
    ++exponent;
  }
  if (exponent > 30) return Status::kOutOfRange;
  if (exponent < -31) {
    *out = {0, 0};
    return Status::kOk;
  }
  *out = {static_cast<int32_t>(q), static_cast<int32_t>(exponent)};
  return Status::kOk;
}

// The real value a pair stands for (tests, reports).
inline double dequantize_multiplier(const QuantizedMultiplier& m) {
  return std::ldexp(static_cast<double>(m.multiplier), m.shift - 31);
}

}  // namespace curio::nn
