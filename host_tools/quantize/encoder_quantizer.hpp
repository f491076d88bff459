// Float encoder → int8 encoder (TFLite/CMSIS-NN int8 scheme): activations asymmetric per tensor
// from calibrated ranges, weights symmetric per output channel in [−127, 127], int32 bias at scale
// s_in·s_w[c], rescales as Q31 multiplier + shift, PyTorch NCHW/OIHW → NHWC/OHWI (fc1's columns
// included). The last layer has int16 weights, stays int32 and is dequantized in float.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "host_tools/model_io/float_encoder.hpp"
#include "host_tools/model_io/float_model.hpp"
#include "firmware/nn/encoder_model.hpp"
#include "host_tools/quantize/calibration.hpp"

namespace curio::quantize {

inline constexpr const char* kQuantizerVersion = "curio-quantize 4";

// How a post-ReLU activation tensor is scaled. kPerTensor: one scale (TFLite). kPerChannel:
// one scale per channel with the common zero point −128; the consuming layer folds the
// scales into its weights before they are quantized per output row, so the firmware
// kernels and their arithmetic are the same either way.
enum class ActivationScales { kPerTensor, kPerChannel };
const char* to_string(ActivationScales s);
bool parse_activation_scales(const std::string& text, ActivationScales* out);

// real = scale[c]·(q − zero_point); scale has one entry (per tensor) or one per channel.
struct ActivationQuant {
  std::vector<double> scale{1.0};
  int32_t zero_point = 0;
  double scale_of(size_t channel) const { return scale.size() == 1 ? scale[0] : scale[channel]; }
};

// Tensors the quantizer calibrates: the outputs of conv0..conv3, fc1, fc2 (all post-ReLU).
inline constexpr int kCalibratedTensors = 6;
inline constexpr std::array<const char*, kCalibratedTensors> kCalibratedTensorNames = {
    "conv0", "conv1", "conv2", "conv3", "fc1", "fc2"};

// Per-channel min/max of every calibrated tensor.
struct ActivationRanges {
  std::array<std::vector<double>, kCalibratedTensors> min;
  std::array<std::vector<double>, kCalibratedTensors> max;
  int images = 0;
  double tensor_min(int t) const;
  double tensor_max(int t) const;
};

// Min/max of every channel of every calibrated tensor over the camera frames (seen as
// p/255 by the float encoder, i.e. exactly what the firmware sees).
ActivationRanges calibrate(const model_io::FloatEncoder& encoder,
                           const std::vector<CameraFrame>& frames);

// Range widened to include 0, spread over the 256 int8 levels; zero point rounded and
// clamped to [−128, 127]. An empty range (dead layer) gets scale 1/255.
ActivationQuant activation_quant(double min, double max);

struct HostLayer {
  std::vector<int8_t> filter;  // NHWC / [out, in] with NHWC columns
  std::vector<int32_t> bias;   // at acc_scale
  std::vector<int32_t> multiplier;
  std::vector<int32_t> shift;
  std::vector<double> acc_scale;  // real value of one unit of the int32 sum, per output
  ActivationQuant input;
  ActivationQuant output;
};

// The latent layer's int16 weights use ±16,383 (see nn::LatentLayer).
inline constexpr int32_t kLatentWeightLevel = 16383;

struct HostLatentLayer {
  std::vector<int16_t> filter;  // [20, 256]
  std::vector<int32_t> bias;
  std::vector<float> scale;  // = acc_scale, as the firmware multiplies it
  std::vector<double> acc_scale;
  ActivationQuant input;
};

struct QuantizedEncoder {
  std::array<HostLayer, nn::kConvLayers> conv;
  HostLayer fc1;
  HostLayer fc2;
  HostLatentLayer latent;
  ActivationRanges ranges;
  ActivationScales scales = ActivationScales::kPerTensor;

  // A view for nn::Encoder; points into this object (keep it alive, do not move it).
  nn::EncoderModel model() const;
};

// Throws model_io::ModelFormatError for a model without a valid encoder, and
// std::runtime_error when a bias or rescale does not fit its integer format.
QuantizedEncoder quantize_encoder(const model_io::FloatModel& model, const ActivationRanges& ranges,
                                  ActivationScales scales);

// Removes the int8 path's mean error on the latent outputs: adds to each latent row's
// int32 bias the rounded mean of (float − int8) over the calibration frames, in that row's
// accumulator units. Returns the largest correction applied (in output units).
double correct_latent_bias(const model_io::FloatEncoder& float_encoder,
                           const std::vector<CameraFrame>& frames, QuantizedEncoder* encoder);

// The whole quantization on calibration frames: calibrate, quantize, correct the latent
// bias. What curio-quantize runs.
QuantizedEncoder quantize_calibrated(const model_io::FloatModel& model,
                                     const model_io::FloatEncoder& float_encoder,
                                     const std::vector<CameraFrame>& frames,
                                     ActivationScales scales);

}  // namespace curio::quantize
