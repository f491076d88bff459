// FNV-1a (32 bit) over integers, float bit patterns and an Explorer archive: the checksums
// that the host (curio-controller --print-checksum, the tests) and the Cortex-M7 images print
// and compare. Firmware-clean: it is compiled into the QEMU images.
#pragma once
#include <cstdint>
#include <cstring>

#include "firmware/explore/archive.hpp"
#include "firmware/explore/config.hpp"

namespace curio {

struct Fnv1a {
  uint32_t h = 2166136261u;
  // Little-endian byte by byte, whatever the machine.
  void add_u32(uint32_t v) {
    for (int i = 0; i < 4; ++i) {
      h ^= (v >> (8 * i)) & 0xFFu;
      h *= 16777619u;
    }
  }
  void add_u64(uint64_t v) {
    add_u32(static_cast<uint32_t>(v));
    add_u32(static_cast<uint32_t>(v >> 32));
  }
  void add_float(float f) {
    uint32_t v;
    std::memcpy(&v, &f, sizeof v);
    add_u32(v);
  }
  // Every archived episode in order: its θ (regenerated), then its outcome.
  void add_archive(const Archive& a) {
    float theta[kThetaDim];
    for (int i = 0; i < a.size(); ++i) {
      a.theta(i, theta);
      for (float t : theta) add_float(t);
      for (int d = 0; d < a.outcome_dim(); ++d) add_float(a.outcome(i, d));
    }
  }
};

}  // namespace curio
