// Seeded, portable pseudo-random generator (PCG32, O'Neill 2014) with uniform and
// Gaussian draws. Same seed → same sequence on every platform; no global state.
#pragma once
#include <cmath>
#include <cstdint>

namespace curio {

class Prng {
 public:
  explicit Prng(uint64_t seed = 0, uint64_t stream = 0) { reseed(seed, stream); }

  void reseed(uint64_t seed, uint64_t stream = 0) {
    state_ = 0u;
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
    has_spare_ = false;
  }

  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * kMultiplier + inc_;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((0u - rot) & 31u));
  }

  // Skips `delta` next_u32() steps in O(log delta) (Brown, "Random number generation with
  // arbitrary strides", 1994): the state afterwards equals `delta` calls of next_u32(). The
  // Gaussian spare is left as it is; the caller decides whether it belongs to the position reached.
  void advance(uint64_t delta) {
    uint64_t mult = kMultiplier, plus = inc_;
    uint64_t acc_mult = 1u, acc_plus = 0u;
    while (delta > 0u) {
      if ((delta & 1u) != 0u) {
        acc_mult *= mult;
        acc_plus = acc_plus * mult + plus;
      }
      plus = (mult + 1u) * plus;
      mult *= mult;
      delta >>= 1u;
    }
    state_ = acc_mult * state_ + acc_plus;
  }

  // Uniform in the open interval (0, 1), 53 bits.
  double uniform01() {
    const uint64_t hi = next_u32() >> 5;  // 27 bits
    const uint64_t lo = next_u32() >> 6;  // 26 bits
    return (static_cast<double>((hi << 26) | lo) + 0.5) * (1.0 / 9007199254740992.0);
  }

  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }

  // next_u32() steps per uniform01() and per Box–Muller pair of normal() values.
  static constexpr uint64_t kStepsPerUniform = 2u;
  static constexpr uint64_t kStepsPerNormalPair = 2u * kStepsPerUniform;

  // Standard normal by the Box–Muller transform (both values used: normal value 2p is the
  // cosine of pair p, value 2p + 1 its sine, kept as the spare for the next call).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = uniform01();
    const double u2 = uniform01();
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double a = 6.283185307179586476925 * u2;
    spare_ = r * std::sin(a);
    has_spare_ = true;
    return r * std::cos(a);
  }

  // Index uniform in [0, n), unbiased (Lemire's rejection).
  uint32_t below(uint32_t n) {
    uint64_t m = static_cast<uint64_t>(next_u32()) * n;
    auto low = static_cast<uint32_t>(m);
    if (low < n) {
      const uint32_t threshold = (0u - n) % n;
      while (low < threshold) {
        m = static_cast<uint64_t>(next_u32()) * n;
        low = static_cast<uint32_t>(m);
      }
    }
    return static_cast<uint32_t>(m >> 32);
  }

 private:
  static constexpr uint64_t kMultiplier = 6364136223846793005ULL;
  uint64_t state_ = 0;
  uint64_t inc_ = 1;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace curio
