// SPEC §3's encoder as LibTorch fp32 modules with the weights of a float model file: what the
// benchmarks put beside the int8 encoder (bench_encoder_torch.cpp, bench_encoder_engines.cpp).
#pragma once
#include <torch/torch.h>

#include <string>

#include "host_tools/model_io/encoder_spec.hpp"
#include "host_tools/model_io/float_model.hpp"

namespace curio::nn::bench {

// SPEC §3's encoder as LibTorch modules, weights from the float model file.
struct TorchEncoder {
  torch::nn::Sequential net;

  explicit TorchEncoder(const model_io::FloatModel& model) {
    auto conv = [](int64_t c_in) {
      return torch::nn::Conv2d(
          torch::nn::Conv2dOptions(c_in, model_io::kConvChannels, model_io::kKernel)
              .stride(model_io::kStride)
              .padding(model_io::kPad));
    };
    net = torch::nn::Sequential(
        conv(3), torch::nn::ReLU(), conv(32), torch::nn::ReLU(), conv(32), torch::nn::ReLU(),
        conv(32), torch::nn::ReLU(), torch::nn::Flatten(),
        torch::nn::Linear(model_io::kFlatten, model_io::kHidden), torch::nn::ReLU(),
        torch::nn::Linear(model_io::kHidden, model_io::kHidden), torch::nn::ReLU(),
        torch::nn::Linear(model_io::kHidden, model_io::kEncoderOutputs));
    const char* names[] = {"enc.conv0", "enc.conv1", "enc.conv2", "enc.conv3",
                           "enc.fc1",   "enc.fc2",   "enc.fc_out"};
    const int modules[] = {0, 2, 4, 6, 9, 11, 13};
    torch::NoGradGuard no_grad;
    for (int i = 0; i < 7; ++i) {
      for (const char* part : {"weight", "bias"}) {
        const model_io::FloatTensor* t = model.find(std::string(names[i]) + "." + part);
        auto param = net[static_cast<size_t>(modules[i])]->named_parameters()[part];
        param.copy_(torch::from_blob(const_cast<float*>(t->data.data()), param.sizes()));
      }
    }
    net->eval();
  }
};

}  // namespace curio::nn::bench
