#include "host_tools/quantize/encoder_quantizer.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>

#include "host_tools/model_io/encoder_spec.hpp"
#include "firmware/nn/encoder.hpp"
#include "firmware/nn/quantize_multiplier.hpp"

namespace curio::quantize {
namespace {

namespace mio = curio::model_io;

static_assert(mio::kImageSize == nn::kImageSize && mio::kConvChannels == nn::kConvChannels &&
                  mio::kFlatten == nn::kFlatten && mio::kHidden == nn::kHidden &&
                  mio::kLatents == nn::kLatents && mio::kKernel == nn::kKernelSize,
              "model_io's encoder spec and the firmware's encoder arch must agree");

// Input of the firmware encoder: camera byte p as q = p − 128, scale 1/255.
const ActivationQuant kImageQuant{{1.0 / 255.0}, -128};

// A layer's weights already permuted to the firmware's column order, with the input
// channel every column reads.
struct FloatRows {
  size_t rows = 0;
  size_t cols = 0;
  std::vector<double> w;  // [rows][cols]
  std::function<size_t(size_t col)> channel_of;
};

struct QuantizedRows {
  std::vector<int32_t> q;  // in [−max_level, max_level]
  std::vector<int32_t> bias;
  std::vector<double> acc_scale;
};

// Folds the input scales into the weights (w·s_in[channel]), then quantizes each row
// symmetrically to [−max_level, max_level] (round half away from zero) and the bias at the
// row's accumulator scale.
QuantizedRows quantize_rows(const std::string& name, const FloatRows& f,
                            const std::vector<float>& bias, const ActivationQuant& in,
                            int32_t max_level) {
  const auto level = static_cast<double>(max_level);
  QuantizedRows r;
  r.q.resize(f.w.size());
  r.bias.resize(f.rows);
  r.acc_scale.resize(f.rows);
  std::vector<double> folded(f.cols);
  for (size_t o = 0; o < f.rows; ++o) {
    double m = 0.0;
    for (size_t k = 0; k < f.cols; ++k) {
      folded[k] = f.w[o * f.cols + k] * in.scale_of(f.channel_of(k));
      m = std::max(m, std::abs(folded[k]));
    }
    // An all-zero row keeps the input's scale so its bias still quantizes sensibly.
    const double s = m > 0.0 ? m / level : in.scale_of(0);
    r.acc_scale[o] = s;
    for (size_t k = 0; k < f.cols; ++k) {
      r.q[o * f.cols + k] =
          static_cast<int32_t>(std::clamp(std::round(folded[k] / s), -level, level));
    }
    const double b = std::round(static_cast<double>(bias[o]) / s);
    if (std::abs(b) > static_cast<double>(std::numeric_limits<int32_t>::max())) {
      throw std::runtime_error(name + " bias[" + std::to_string(o) + "] = " +
                               std::to_string(bias[o]) + " does not fit int32 at its scale");
    }
    r.bias[o] = static_cast<int32_t>(b);
  }
  return r;
}

HostLayer make_layer(const std::string& name, const FloatRows& f, const std::vector<float>& bias,
                     const ActivationQuant& in, const ActivationQuant& out) {
  QuantizedRows r = quantize_rows(name, f, bias, in, 127);
  HostLayer L{std::vector<int8_t>(r.q.begin(), r.q.end()),
              std::move(r.bias),
              {},
              {},
              std::move(r.acc_scale),
              in,
              out};
  for (size_t o = 0; o < f.rows; ++o) {
    const double real = L.acc_scale[o] / out.scale_of(o);
    nn::QuantizedMultiplier m;
    if (nn::quantize_multiplier(real, &m) != nn::Status::kOk) {
      throw std::runtime_error(name + ": rescale " + std::to_string(real) + " of output " +
                               std::to_string(o) + " has no Q31 multiplier + shift");
    }
    L.multiplier.push_back(m.multiplier);
    L.shift.push_back(m.shift);
  }
  return L;
}

const mio::FloatTensor& tensor(const mio::FloatModel& model, const std::string& name) {
  return *model.find(name);
}

// Per-channel scales share the zero point −128, which needs every channel's range to
// start at 0 (true after ReLU).
ActivationQuant tensor_quant(const ActivationRanges& r, int t, ActivationScales scales) {
  const auto ti = static_cast<size_t>(t);
  if (scales == ActivationScales::kPerTensor || r.tensor_min(t) < 0.0) {
    return activation_quant(r.tensor_min(t), r.tensor_max(t));
  }
  ActivationQuant q;
  q.zero_point = -128;
  q.scale.resize(r.max[ti].size());
  double smallest = std::numeric_limits<double>::infinity();
  for (double m : r.max[ti]) {
    if (m > 0.0) smallest = std::min(smallest, m / 255.0);
  }
  if (!std::isfinite(smallest)) smallest = 1.0 / 255.0;
  // A channel never seen active gets the smallest live scale: if it ever fires it is
  // clipped to a tiny value instead of claiming weight range in the next layer.
  for (size_t c = 0; c < q.scale.size(); ++c) {
    q.scale[c] = r.max[ti][c] > 0.0 ? r.max[ti][c] / 255.0 : smallest;
  }
  return q;
}

}  // namespace

const char* to_string(ActivationScales s) {
  return s == ActivationScales::kPerChannel ? "per-channel" : "per-tensor";
}

bool parse_activation_scales(const std::string& text, ActivationScales* out) {
  if (text == "per-tensor") {
    *out = ActivationScales::kPerTensor;
  } else if (text == "per-channel") {
    *out = ActivationScales::kPerChannel;
  } else {
    return false;
  }
  return true;
}

double ActivationRanges::tensor_min(int t) const {
  const auto& v = min[static_cast<size_t>(t)];
  return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end());
}

double ActivationRanges::tensor_max(int t) const {
  const auto& v = max[static_cast<size_t>(t)];
  return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

ActivationRanges calibrate(const mio::FloatEncoder& encoder,
                           const std::vector<CameraFrame>& frames) {
  ActivationRanges r;
  const size_t channels[kCalibratedTensors] = {mio::kConvChannels, mio::kConvChannels,
                                               mio::kConvChannels, mio::kConvChannels,
                                               mio::kHidden,       mio::kHidden};
  for (size_t t = 0; t < kCalibratedTensors; ++t) {
    r.min[t].assign(channels[t], std::numeric_limits<double>::infinity());
    r.max[t].assign(channels[t], -std::numeric_limits<double>::infinity());
  }
  mio::EncoderTrace trace;
  for (const CameraFrame& frame : frames) {
    const std::vector<float> image = frame_to_float(frame);
    encoder.forward(image.data(), &trace);
    const std::array<const std::vector<float>*, kCalibratedTensors> tensors = {
        &trace.conv[0], &trace.conv[1], &trace.conv[2], &trace.conv[3], &trace.fc1, &trace.fc2};
    for (size_t t = 0; t < kCalibratedTensors; ++t) {
      const size_t per_channel = tensors[t]->size() / channels[t];  // CHW: channel-major
      for (size_t i = 0; i < tensors[t]->size(); ++i) {
        const size_t c = i / per_channel;
        const double v = (*tensors[t])[i];
        r.min[t][c] = std::min(r.min[t][c], v);
        r.max[t][c] = std::max(r.max[t][c], v);
      }
    }
    ++r.images;
  }
  return r;
}

ActivationQuant activation_quant(double min, double max) {
  min = std::min(min, 0.0);
  max = std::max(max, 0.0);
  const double scale = max > min ? (max - min) / 255.0 : 1.0 / 255.0;
  const double zp = std::round(-128.0 - min / scale);
  return {{scale}, static_cast<int32_t>(std::clamp(zp, -128.0, 127.0))};
}

QuantizedEncoder quantize_encoder(const mio::FloatModel& model, const ActivationRanges& ranges,
                                  ActivationScales scales) {
  mio::validate_encoder(model);
  if (ranges.images <= 0) throw std::runtime_error("calibration saw no images");
  QuantizedEncoder q;
  q.ranges = ranges;
  q.scales = scales;
  std::array<ActivationQuant, kCalibratedTensors> act;
  for (int t = 0; t < kCalibratedTensors; ++t)
    act[static_cast<size_t>(t)] = tensor_quant(ranges, t, scales);

  // Convolutions: OIHW → OHWI; column (ky·4 + kx)·C_in + ci reads channel ci.
  for (int i = 0; i < nn::kConvLayers; ++i) {
    const std::string name = "enc.conv" + std::to_string(i);
    const auto& w = tensor(model, name + ".weight").data;
    const auto c_in = static_cast<size_t>(nn::conv_input_channels(i));
    const size_t k = nn::kKernelSize;
    FloatRows f{nn::kConvChannels, k * k * c_in, std::vector<double>(w.size()),
                [c_in](size_t col) { return col % c_in; }};
    for (size_t co = 0; co < f.rows; ++co)
      for (size_t ci = 0; ci < c_in; ++ci)
        for (size_t ky = 0; ky < k; ++ky)
          for (size_t kx = 0; kx < k; ++kx) {
            f.w[((co * k + ky) * k + kx) * c_in + ci] = w[((co * c_in + ci) * k + ky) * k + kx];
          }
    q.conv[static_cast<size_t>(i)] = make_layer(
        name, f, tensor(model, name + ".bias").data,
        i == 0 ? kImageQuant : act[static_cast<size_t>(i - 1)], act[static_cast<size_t>(i)]);
  }

  // fc1: NCHW-flatten column c·16 + y·4 + x → NHWC-flatten column (y·4 + x)·32 + c.
  {
    const auto& w = tensor(model, "enc.fc1.weight").data;
    const size_t s = nn::kFinalMapSize;
    const size_t ch = nn::kConvChannels;
    FloatRows f{nn::kHidden, nn::kFlatten, std::vector<double>(w.size()),
                [ch](size_t col) { return col % ch; }};
    for (size_t o = 0; o < f.rows; ++o)
      for (size_t c = 0; c < ch; ++c)
        for (size_t y = 0; y < s; ++y)
          for (size_t x = 0; x < s; ++x) {
            f.w[o * f.cols + (y * s + x) * ch + c] = w[o * f.cols + (c * s + y) * s + x];
          }
    q.fc1 = make_layer("enc.fc1", f, tensor(model, "enc.fc1.bias").data, act[3], act[4]);
  }
  auto direct = [&](const std::string& name, size_t rows) {
    const auto& w = tensor(model, name + ".weight").data;
    return FloatRows{rows, w.size() / rows, std::vector<double>(w.begin(), w.end()),
                     [](size_t col) { return col; }};
  };
  q.fc2 = make_layer("enc.fc2", direct("enc.fc2", nn::kHidden), tensor(model, "enc.fc2.bias").data,
                     act[4], act[5]);
  {
    QuantizedRows r =
        quantize_rows("enc.fc_out", direct("enc.fc_out", nn::kLatentOutputs),
                      tensor(model, "enc.fc_out.bias").data, act[5], kLatentWeightLevel);
    HostLatentLayer& L = q.latent;
    L.filter.assign(r.q.begin(), r.q.end());
    L.bias = std::move(r.bias);
    L.acc_scale = std::move(r.acc_scale);
    L.input = act[5];
    for (double s : L.acc_scale) L.scale.push_back(static_cast<float>(s));
  }
  return q;
}

double correct_latent_bias(const mio::FloatEncoder& float_encoder,
                           const std::vector<CameraFrame>& frames, QuantizedEncoder* q) {
  if (frames.empty()) return 0.0;
  std::array<double, nn::kLatentOutputs> diff{};
  auto encoder = std::make_unique<nn::Encoder>(q->model());
  mio::EncoderTrace trace;
  for (const CameraFrame& frame : frames) {
    float mu[nn::kLatents];
    float log_var[nn::kLatents];
    if (encoder->encode(frame.data(), mu, log_var) != nn::Status::kOk) {
      throw std::runtime_error("int8 encoder failed on a calibration frame");
    }
    float_encoder.forward(frame_to_float(frame).data(), &trace);
    for (size_t j = 0; j < nn::kLatents; ++j) {
      diff[j] += trace.out[j] - static_cast<double>(mu[j]);
      diff[nn::kLatents + j] += trace.out[nn::kLatents + j] - static_cast<double>(log_var[j]);
    }
  }
  double largest = 0.0;
  for (size_t j = 0; j < diff.size(); ++j) {
    const double mean = diff[j] / static_cast<double>(frames.size());
    const double units = std::round(mean / q->latent.acc_scale[j]);
    const double biased = static_cast<double>(q->latent.bias[j]) + units;
    if (std::abs(biased) > static_cast<double>(std::numeric_limits<int32_t>::max())) continue;
    q->latent.bias[j] = static_cast<int32_t>(biased);
    largest = std::max(largest, std::abs(mean));
  }
  return largest;
}

QuantizedEncoder quantize_calibrated(const mio::FloatModel& model,
                                     const mio::FloatEncoder& float_encoder,
                                     const std::vector<CameraFrame>& frames,
                                     ActivationScales scales) {
  QuantizedEncoder q = quantize_encoder(model, calibrate(float_encoder, frames), scales);
  correct_latent_bias(float_encoder, frames, &q);
  return q;
}

nn::EncoderModel QuantizedEncoder::model() const {
  auto layer = [](const HostLayer& L) {
    return nn::QuantizedLayer{L.filter.data(), L.bias.data(),       L.multiplier.data(),
                              L.shift.data(),  -L.input.zero_point, L.output.zero_point};
  };
  nn::EncoderModel m;
  for (size_t i = 0; i < conv.size(); ++i) m.conv[i] = layer(conv[i]);
  m.fc1 = layer(fc1);
  m.fc2 = layer(fc2);
  m.latent = {latent.filter.data(), latent.bias.data(), latent.scale.data(),
              -latent.input.zero_point};
  return m;
}

}  // namespace curio::quantize
