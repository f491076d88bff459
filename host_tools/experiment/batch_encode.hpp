// Many camera frames through the int8 encoder on several threads: the frames split into one
// contiguous share per thread, each thread with its own nn::Encoder (Encoder::encode_batch).
// Every frame is encoded on its own, so the outputs do not depend on the thread count.
#pragma once
#include <cstdint>
#include <string>

#include "firmware/nn/encoder_model.hpp"

namespace curio::lab {

// frames: count × nn::kImageBytes; mu (and log_var, may be nullptr): count × nn::kLatents.
// Returns "" or one line naming the first frame the encoder refused.
std::string encode_frames(const nn::EncoderModel& model, const uint8_t* frames, int32_t count,
                          int threads, float* mu, float* log_var);

}  // namespace curio::lab
