// The synthetic model's generated header (built at test time by curio-quantize), compiled
// in a firmware-flags translation unit: proves the emitted header builds as firmware.
#pragma once
#include "firmware/nn/encoder_model.hpp"

namespace curio::nn::testing {

const EncoderModel& synthetic_firmware_model();
const int* synthetic_kl_order();  // 10 entries

// How the header was generated (must match tests/nn/CMakeLists.txt).
inline constexpr uint64_t kSyntheticSeed = 5;
inline constexpr int kSyntheticCalibrationImages = 100;
inline constexpr uint64_t kSyntheticCalibrationSeed = 1;

}  // namespace curio::nn::testing
