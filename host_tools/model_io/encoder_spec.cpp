#include "host_tools/model_io/encoder_spec.hpp"

#include <cmath>

#include "host_tools/model_io/float_model.hpp"

namespace curio::model_io {

const std::vector<TensorSpec>& encoder_tensor_specs() {
  static const std::vector<TensorSpec> specs = [] {
    std::vector<TensorSpec> s;
    for (int i = 0; i < kConvLayers; ++i) {
      const int64_t c_in = i == 0 ? kImageChannels : kConvChannels;
      const std::string p = "enc.conv" + std::to_string(i);
      s.push_back({p + ".weight", {kConvChannels, c_in, kKernel, kKernel}});
      s.push_back({p + ".bias", {kConvChannels}});
    }
    s.push_back({"enc.fc1.weight", {kHidden, kFlatten}});
    s.push_back({"enc.fc1.bias", {kHidden}});
    s.push_back({"enc.fc2.weight", {kHidden, kHidden}});
    s.push_back({"enc.fc2.bias", {kHidden}});
    s.push_back({"enc.fc_out.weight", {kEncoderOutputs, kHidden}});
    s.push_back({"enc.fc_out.bias", {kEncoderOutputs}});
    return s;
  }();
  return specs;
}

void validate_encoder(const FloatModel& model) {
  for (const auto& spec : encoder_tensor_specs()) {
    const FloatTensor& t = model.require(spec.name, spec.dims);
    for (float v : t.data) {
      if (!std::isfinite(v)) {
        throw ModelFormatError("tensor '" + spec.name + "' holds a non-finite value");
      }
    }
  }
}

}  // namespace curio::model_io
