// Float reference of the SPEC §3 encoder, computed straight from the PyTorch-layout
// tensors of a float model file (NCHW activations, OIHW filters) so that it checks the
// quantizer's NHWC permutation instead of sharing it. Host only (Eigen).
#pragma once
#include <array>
#include <vector>

#include "host_tools/model_io/encoder_spec.hpp"
#include "host_tools/model_io/float_model.hpp"

namespace curio::model_io {

// Every activation of one forward pass, for calibration and debugging.
struct EncoderTrace {
  std::array<std::vector<float>, kConvLayers> conv;  // post-ReLU, CHW
  std::vector<float> fc1;                            // post-ReLU, 256
  std::vector<float> fc2;                            // post-ReLU, 256
  std::array<float, kEncoderOutputs> out{};          // μ (0–9), log-variance (10–19)
};

class FloatEncoder {
 public:
  // Validates the encoder tensors (throws ModelFormatError) and keeps a copy of them.
  explicit FloatEncoder(const FloatModel& model);

  // image: 64×64×3 HWC floats in [0, 1] (sim::Image). Returns the encoder mean μ.
  std::array<float, kLatents> mu(const float* image_hwc) const;

  // The same forward pass, recording every layer's output.
  void forward(const float* image_hwc, EncoderTrace* trace) const;

 private:
  struct Layer {
    std::vector<float> weight;  // PyTorch layout
    std::vector<float> bias;
  };
  std::array<Layer, kConvLayers> conv_;
  Layer fc1_, fc2_, fc_out_;
};

}  // namespace curio::model_io
