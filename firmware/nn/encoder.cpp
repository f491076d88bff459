#include "firmware/nn/encoder.hpp"

namespace curio::nn {
Status Encoder::encode(const uint8_t* image, float mu[kLatents], float log_var[kLatents]) {
  if (image == nullptr || mu == nullptr) {
    ++faults_;
    return Status::kArgumentError;
  }
  const Status status = run(image, mu, log_var);
  if (status != Status::kOk) {
    ++faults_;
  } else {
    ++encodes_;
  }
  return status;
}

Encoder::LayerOutput Encoder::layer_output(int32_t layer) const {
  // Layer i writes buffer (i + 1) % 2 (encoder.hpp's arena layout); the FCs go on alternating.
  const int8_t* const buffers[2] = {arena_ + arena::kPingOffset, arena_ + arena::kPongOffset};
  if (layer >= 0 && layer < kConvLayers) return {buffers[(layer + 1) % 2], arena::map_bytes(layer + 1)};
  if (layer == kConvLayers || layer == kConvLayers + 1) return {buffers[(layer + 1) % 2], kHidden};
  if (layer == kConvLayers + 2) return {latent_sums_, static_cast<int32_t>(sizeof latent_sums_)};
  return {nullptr, 0};
}

Status Encoder::encode_batch(const uint8_t* images, int32_t count, float* mu, float* log_var,
                             int32_t* done) {
  if (done != nullptr) *done = 0;
  if (count == 0) return Status::kOk;
  if (images == nullptr || mu == nullptr || count < 0) {
    ++faults_;
    return Status::kArgumentError;
  }
  for (int32_t i = 0; i < count; ++i) {
    const Status s = encode(images + i * kImageBytes, mu + i * kLatents,
                            log_var != nullptr ? log_var + i * kLatents : nullptr);
    if (s != Status::kOk) return s;
    if (done != nullptr) *done = i + 1;
  }
  return Status::kOk;
}

Status Encoder::run(const uint8_t* image, float mu[kLatents], float log_var[kLatents]) {
  int8_t* const buffers[2] = {arena_ + arena::kPingOffset, arena_ + arena::kPongOffset};
  const Context scratch{arena_ + arena::kScratchOffset, arena::kScratchBytes};

  // Camera byte p → q = p − 128 (scale 1/255, zero point −128).
  for (int32_t i = 0; i < kImageBytes; ++i) {
    buffers[0][i] = static_cast<int8_t>(static_cast<int32_t>(image[i]) - 128);
  }
  probe(-1);

  auto conv_params = [this](int32_t i) { return conv_params_of(model_.conv[i]); };
  if (arena::kPreparedBytes > 0 && !filters_prepared_) {
    for (int32_t i = 0; i < kConvLayers; ++i) {
      const Status s = conv_s8_prepare(conv_params(i), arena::conv_input_dims(i), arena::conv_filter_dims(i),
                                       model_.conv[i].filter, prepared_ + arena::prepared_offset(i));
      if (s != Status::kOk) return s;
    }
    filters_prepared_ = true;
  }

  for (int32_t i = 0; i < kConvLayers; ++i) {
    const QuantizedLayer& layer = model_.conv[i];
    const Dims out{1, conv_map_size(i + 1), conv_map_size(i + 1), kConvChannels};
    const int8_t* prepared = arena::kPreparedBytes > 0 ? prepared_ + arena::prepared_offset(i) : nullptr;
    const Status s = conv_s8(scratch, conv_params(i), {layer.multiplier, layer.shift},
                             arena::conv_input_dims(i), buffers[i % 2], arena::conv_filter_dims(i),
                             layer.filter, layer.bias, out, buffers[(i + 1) % 2], prepared);
    if (s != Status::kOk) return s;
    probe(i);
  }
  static_assert(kConvLayers % 2 == 0, "conv3's output lands in buffer 0");

  // The NHWC flatten of the 4×4×32 map is the buffer itself (the quantizer permuted
  // fc1's columns to match).
  const QuantizedLayer* fcs[2] = {&model_.fc1, &model_.fc2};
  const int32_t fc_inputs[2] = {kFlatten, kHidden};
  for (int32_t i = 0; i < 2; ++i) {
    const QuantizedLayer& layer = *fcs[i];
    FcParams params;
    params.input_offset = layer.input_offset;
    params.output_offset = layer.output_offset;
    params.activation = relu_from(layer.output_offset);
    const Status s = fully_connected_s8(scratch, params, {layer.multiplier, layer.shift},
                                        {1, fc_inputs[i], kHidden}, buffers[i % 2], layer.filter,
                                        layer.bias, buffers[(i + 1) % 2]);
    if (s != Status::kOk) return s;
    probe(kConvLayers + i);
  }

  const LatentLayer& latent = model_.latent;
  if (latent.scale == nullptr) return Status::kArgumentError;
  int32_t* const sums = latent_sums_;
  const Status s =
      fully_connected_s8_w16_s32(scratch, latent.input_offset, {1, kHidden, kLatentOutputs},
                                 buffers[0], latent.filter, latent.bias, sums);
  if (s != Status::kOk) return s;
  probe(kConvLayers + 2);
  for (int32_t j = 0; j < kLatents; ++j) {
    mu[j] = latent.scale[j] * static_cast<float>(sums[j]);
    if (log_var != nullptr) {
      log_var[j] = latent.scale[kLatents + j] * static_cast<float>(sums[kLatents + j]);
    }
  }
  return Status::kOk;
}

}  // namespace curio::nn
