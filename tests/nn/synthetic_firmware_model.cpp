// Compiled with the firmware flags (-fno-exceptions -fno-rtti -Wconversion -Werror).
#include "tests/nn/synthetic_firmware_model.hpp"

#include "tests/nn/synthetic_weights.hpp"

namespace curio::nn::testing {

const EncoderModel& synthetic_firmware_model() {
  return synthetic::kEncoderModel;
}
const int* synthetic_kl_order() {
  return synthetic::kKlOrder;
}

}  // namespace curio::nn::testing
