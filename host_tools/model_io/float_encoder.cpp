#include "host_tools/model_io/float_encoder.hpp"

#include <Eigen/Dense>

namespace curio::model_io {
namespace {

using RowMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ColMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor>;

// conv 4×4, stride 2, pad 1 + ReLU on a CHW map (size×size×c_in) → CHW (size/2).
void conv_relu(const std::vector<float>& in, int c_in, int size, const std::vector<float>& w,
               const std::vector<float>& b, std::vector<float>* out) {
  const int out_size = size / kStride;
  const int k = c_in * kKernel * kKernel;
  const int p = out_size * out_size;
  // im2col: column = output pixel, row = (c, ky, kx) in OIHW's inner order.
  ColMatrix cols = ColMatrix::Zero(k, p);
  for (int oy = 0; oy < out_size; ++oy) {
    for (int ox = 0; ox < out_size; ++ox) {
      const int col = oy * out_size + ox;
      for (int c = 0; c < c_in; ++c) {
        for (int ky = 0; ky < kKernel; ++ky) {
          const int iy = oy * kStride - kPad + ky;
          if (iy < 0 || iy >= size) continue;
          for (int kx = 0; kx < kKernel; ++kx) {
            const int ix = ox * kStride - kPad + kx;
            if (ix < 0 || ix >= size) continue;
            cols((c * kKernel + ky) * kKernel + kx, col) =
                in[static_cast<size_t>((c * size + iy) * size + ix)];
          }
        }
      }
    }
  }
  const Eigen::Map<const RowMatrix> wm(w.data(), kConvChannels, k);
  const Eigen::Map<const Eigen::VectorXf> bv(b.data(), kConvChannels);
  out->assign(static_cast<size_t>(kConvChannels * p), 0.0f);
  Eigen::Map<RowMatrix> om(out->data(), kConvChannels, p);
  om.noalias() = wm * cols;
  om.colwise() += bv;
  om = om.cwiseMax(0.0f);
}

void fc(const std::vector<float>& in, const std::vector<float>& w, const std::vector<float>& b,
        bool relu, float* out) {
  const auto n_out = static_cast<Eigen::Index>(b.size());
  const auto n_in = static_cast<Eigen::Index>(in.size());
  const Eigen::Map<const RowMatrix> wm(w.data(), n_out, n_in);
  const Eigen::Map<const Eigen::VectorXf> x(in.data(), n_in);
  const Eigen::Map<const Eigen::VectorXf> bv(b.data(), n_out);
  Eigen::Map<Eigen::VectorXf> y(out, n_out);
  y.noalias() = wm * x;
  y += bv;
  if (relu) y = y.cwiseMax(0.0f);
}

}  // namespace

FloatEncoder::FloatEncoder(const FloatModel& model) {
  validate_encoder(model);
  auto load = [&](const std::string& prefix) {
    return Layer{model.find(prefix + ".weight")->data, model.find(prefix + ".bias")->data};
  };
  for (int i = 0; i < kConvLayers; ++i)
    conv_[static_cast<size_t>(i)] = load("enc.conv" + std::to_string(i));
  fc1_ = load("enc.fc1");
  fc2_ = load("enc.fc2");
  fc_out_ = load("enc.fc_out");
}

void FloatEncoder::forward(const float* image_hwc, EncoderTrace* trace) const {
  // HWC → CHW.
  std::vector<float> x(static_cast<size_t>(kImageChannels * kImageSize * kImageSize));
  for (int y = 0; y < kImageSize; ++y) {
    for (int xx = 0; xx < kImageSize; ++xx) {
      for (int c = 0; c < kImageChannels; ++c) {
        x[static_cast<size_t>((c * kImageSize + y) * kImageSize + xx)] =
            image_hwc[(y * kImageSize + xx) * kImageChannels + c];
      }
    }
  }
  int size = kImageSize;
  int c_in = kImageChannels;
  const std::vector<float>* in = &x;
  for (size_t i = 0; i < kConvLayers; ++i) {
    conv_relu(*in, c_in, size, conv_[i].weight, conv_[i].bias, &trace->conv[i]);
    in = &trace->conv[i];
    size /= kStride;
    c_in = kConvChannels;
  }
  // CHW flatten is PyTorch's view(-1, 512): exactly the buffer's order.
  trace->fc1.resize(kHidden);
  trace->fc2.resize(kHidden);
  fc(trace->conv[kConvLayers - 1], fc1_.weight, fc1_.bias, true, trace->fc1.data());
  fc(trace->fc1, fc2_.weight, fc2_.bias, true, trace->fc2.data());
  fc(trace->fc2, fc_out_.weight, fc_out_.bias, false, trace->out.data());
}

std::array<float, kLatents> FloatEncoder::mu(const float* image_hwc) const {
  EncoderTrace trace;
  forward(image_hwc, &trace);
  std::array<float, kLatents> m{};
  for (size_t i = 0; i < kLatents; ++i) m[i] = trace.out[i];
  return m;
}

}  // namespace curio::model_io
