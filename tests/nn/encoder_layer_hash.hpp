// Per-layer checksums of the int8 encoder on one fixed frame, so that the Cortex-M7 image
// (tests/board/cycle_budget_main.cpp) and every host kernel path compare each layer's output
// with the host's reference kernels bit for bit, not only the final μ. Firmware-clean (it is
// compiled into the QEMU image). The expected values are generated into
// tests/nn/qemu/encoder_layer_hashes.hpp (tests/nn/encoder_layer_reference.*).
#pragma once
#include <cstdint>

#include "firmware/nn/encoder.hpp"

namespace curio::nn::testing {

inline constexpr int32_t kHashedLayers = kConvLayers + 3;  // 4 convs, fc1, fc2, latent sums

// The frame: byte i is (i · 37) mod 256 (the cycle budget image's synthetic frame).
inline void layer_test_frame(uint8_t* frame) {
  for (int32_t i = 0; i < kImageBytes; ++i) frame[i] = static_cast<uint8_t>((i * 37) & 0xFF);
}

// FNV-1a (32 bit) over bytes.
inline uint32_t hash_bytes(const void* data, int32_t bytes) {
  uint32_t h = 2166136261u;
  const auto* p = static_cast<const uint8_t*>(data);
  for (int32_t i = 0; i < bytes; ++i) {
    h ^= p[i];
    h *= 16777619u;
  }
  return h;
}

// The encoder's probe that hashes each layer's output as it is written.
struct LayerHashes {
  uint32_t hash[kHashedLayers] = {};
  static void probe(void* user, int32_t layer);
  Encoder* encoder = nullptr;
};

inline void LayerHashes::probe(void* user, int32_t layer) {
  auto* self = static_cast<LayerHashes*>(user);
  if (layer < 0 || layer >= kHashedLayers) return;
  const Encoder::LayerOutput o = self->encoder->layer_output(layer);
  self->hash[layer] = hash_bytes(o.data, o.bytes);
}

// Encodes `frame` with `encoder`, hashing every layer into *out. Returns the encode status.
inline Status hash_encoder_layers(Encoder& encoder, const uint8_t* frame, LayerHashes* out) {
  out->encoder = &encoder;
  encoder.set_layer_probe(&LayerHashes::probe, out);
  float mu[kLatents];
  const Status s = encoder.encode(frame, mu);
  encoder.set_layer_probe(nullptr, nullptr);
  return s;
}

}  // namespace curio::nn::testing
