// Result of every nn kernel and of the encoder. Kernels never abort: a bad argument is
// reported here and counted by the caller (see Encoder::faults()).
#pragma once
#include <cstdint>

namespace curio::nn {

enum class Status : uint8_t {
  kOk = 0,
  kArgumentError,   // null pointer, inconsistent dims, misaligned buffer, bad quant params
  kBufferTooSmall,  // scratch smaller than *_get_buffer_size()
  kOutOfRange,      // a real multiplier that a Q31 multiplier and shift cannot represent
};

}  // namespace curio::nn
