#include "host_tools/model_io/float_decoder.hpp"

#include <cmath>
#include <string>

namespace curio::model_io {
namespace {

constexpr int kDeconvOut[4] = {kConvChannels, kConvChannels, kConvChannels, 3};

// Transposed conv 4×4, stride 2, pad 1 on a CHW map (size×size×c_in) → CHW (2·size):
// out[o, y, x] = b[o] + Σ in[i, iy, ix]·w[i, o, ky, kx] over y = 2·iy − 1 + ky, x likewise.
std::vector<float> deconv(const std::vector<float>& in, int c_in, int size, const std::vector<float>& w,
                          const std::vector<float>& b, int c_out, bool relu) {
  const int out_size = size * kStride;
  std::vector<float> out(static_cast<size_t>(c_out * out_size * out_size));
  for (int o = 0; o < c_out; ++o)
    for (int p = 0; p < out_size * out_size; ++p) out[static_cast<size_t>(o * out_size * out_size + p)] = b[static_cast<size_t>(o)];
  for (int i = 0; i < c_in; ++i) {
    for (int iy = 0; iy < size; ++iy) {
      for (int ix = 0; ix < size; ++ix) {
        const float v = in[static_cast<size_t>((i * size + iy) * size + ix)];
        if (v == 0.0f) continue;
        for (int o = 0; o < c_out; ++o) {
          const float* wk = &w[static_cast<size_t>(((i * c_out + o) * kKernel) * kKernel)];
          float* plane = &out[static_cast<size_t>(o * out_size * out_size)];
          for (int ky = 0; ky < kKernel; ++ky) {
            const int y = iy * kStride - kPad + ky;
            if (y < 0 || y >= out_size) continue;
            for (int kx = 0; kx < kKernel; ++kx) {
              const int x = ix * kStride - kPad + kx;
              if (x < 0 || x >= out_size) continue;
              plane[y * out_size + x] += v * wk[ky * kKernel + kx];
            }
          }
        }
      }
    }
  }
  if (relu)
    for (float& v : out) v = v > 0.0f ? v : 0.0f;
  return out;
}

std::vector<float> linear(const std::vector<float>& in, const std::vector<float>& w, const std::vector<float>& b) {
  const size_t n_out = b.size();
  const size_t n_in = in.size();
  std::vector<float> out(n_out);
  for (size_t o = 0; o < n_out; ++o) {
    float s = b[o];
    for (size_t i = 0; i < n_in; ++i) s += w[o * n_in + i] * in[i];
    out[o] = s > 0.0f ? s : 0.0f;  // both decoder FCs are followed by ReLU
  }
  return out;
}

}  // namespace

FloatDecoder::FloatDecoder(const FloatModel& model) {
  auto take = [&model](const std::string& name, const std::vector<int64_t>& w_dims, int64_t n_bias, Layer* l) {
    l->weight = model.require(name + ".weight", w_dims).data;
    l->bias = model.require(name + ".bias", {n_bias}).data;
  };
  take("dec.fc1", {kHidden, kLatents}, kHidden, &fc1_);
  take("dec.fc2", {kFlatten, kHidden}, kFlatten, &fc2_);
  for (int k = 0; k < 4; ++k)
    take("dec.deconv" + std::to_string(k), {kConvChannels, kDeconvOut[k], kKernel, kKernel}, kDeconvOut[k], &deconv_[static_cast<size_t>(k)]);
}

std::vector<float> FloatDecoder::image(const std::array<float, kLatents>& z) const {
  std::vector<float> h = linear(std::vector<float>(z.begin(), z.end()), fc1_.weight, fc1_.bias);
  h = linear(h, fc2_.weight, fc2_.bias);  // 512 = 32×4×4, CHW (PyTorch's view)
  int size = kFinalMapSize;
  for (int k = 0; k < 4; ++k) {
    const Layer& l = deconv_[static_cast<size_t>(k)];
    h = deconv(h, kConvChannels, size, l.weight, l.bias, kDeconvOut[k], k < 3);
    size *= kStride;
  }
  // CHW logits → HWC Bernoulli means.
  std::vector<float> hwc(static_cast<size_t>(size * size * 3));
  for (int c = 0; c < 3; ++c)
    for (int p = 0; p < size * size; ++p)
      hwc[static_cast<size_t>(p * 3 + c)] = 1.0f / (1.0f + std::exp(-h[static_cast<size_t>(c * size * size + p)]));
  return hwc;
}

}  // namespace curio::model_io
