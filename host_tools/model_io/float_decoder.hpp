// The SPEC §3 decoder in plain C++ from a float model file's "dec.*" tensors (PyTorch layout):
// z (10) → FC 256 ReLU → FC 512 ReLU → 32×4×4 → 3 × [transposed conv 32 ch, 4×4, stride 2,
// pad 1, ReLU] → transposed conv 3 ch → sigmoid: the image the model reconstructs from z, as
// host_tools/vae's LibTorch decoder computes it. For tools without LibTorch (curio-encode's
// reconstructions and traversals). Host only.
#pragma once
#include <array>
#include <vector>

#include "host_tools/model_io/encoder_spec.hpp"
#include "host_tools/model_io/float_model.hpp"

namespace curio::model_io {

class FloatDecoder {
 public:
  // Validates the decoder tensors (throws ModelFormatError: "missing tensor" when the file
  // has no decoder, e.g. an encoder-only export) and keeps a copy of them.
  explicit FloatDecoder(const FloatModel& model);

  // z (kLatents) → 64×64×3 HWC image in [0, 1] (the Bernoulli means).
  std::vector<float> image(const std::array<float, kLatents>& z) const;

 private:
  struct Layer {
    std::vector<float> weight;  // PyTorch layout (Linear [out, in]; ConvTranspose2d [in, out, kh, kw])
    std::vector<float> bias;
  };
  Layer fc1_, fc2_;
  std::array<Layer, 4> deconv_;
};

}  // namespace curio::model_io
