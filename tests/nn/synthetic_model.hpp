// A random encoder in the float model format, for tests that need a model before (or
// besides) the trained one: Kaiming-normal weights (std √(2/fan_in), the init the trainer
// uses), small random biases, and a meta JSON with a decreasing KL profile.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "host_tools/model_io/float_model.hpp"
#include "host_tools/model_io/model_meta.hpp"

namespace curio::nn::testing {

std::vector<model_io::FloatTensor> synthetic_encoder_tensors(uint64_t seed);
model_io::ModelMeta synthetic_meta(uint64_t seed);

// Writes <dir>/<name>.cfm and <dir>/<name>.meta.json; returns the .cfm path.
std::string write_synthetic_model(const std::string& dir, const std::string& name, uint64_t seed);

}  // namespace curio::nn::testing
