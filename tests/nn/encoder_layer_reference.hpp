// The shipped β-VAE encoder run layer by layer with the plain reference kernels
// (reference_kernels.hpp) on layer_test_frame(), hashed as encoder_layer_hash.hpp hashes the
// firmware encoder's layers; and the generated header that carries those hashes to the
// Cortex-M7 image (tests/nn/qemu/encoder_layer_hashes.hpp, written by
// curio_nn_make_encoder_layer_hashes, checked for staleness by a host test).
#pragma once
#include <array>
#include <cstdint>
#include <string>

#include "firmware/nn/encoder_model.hpp"
#include "tests/nn/encoder_layer_hash.hpp"

namespace curio::nn::testing {

inline constexpr const char* kEncoderLayerHashesPath = "tests/nn/qemu/encoder_layer_hashes.hpp";

std::array<uint32_t, kHashedLayers> reference_layer_hashes(const EncoderModel& model, const uint8_t* frame);

// The header's text for the shipped β-VAE weights (firmware/nn/models/beta_vae_weights.hpp).
std::string make_encoder_layer_hashes_header();

}  // namespace curio::nn::testing
