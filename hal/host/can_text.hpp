// Frames as text in can-utils' notation, so logs interoperate with cansend/candump -L/canplayer:
//   123#DEADBEEF        classic, 11-bit id (3 hex digits)
//   1FFFFFFF#00         classic, 29-bit id (8 hex digits)
//   123#R               remote request
//   123##1DEADBEEF      FD; the digit after ## is the FD flags (1 = BRS, 2 = ESI)
#pragma once
#include <string>
#include <string_view>

#include "hal/can_frame.hpp"

namespace curio::hal {

std::string format_frame(const CanFrame& frame);

// False when `text` is not a frame in the notation above; FD payloads must have a valid FD
// length (0–8, 12, 16, 20, 24, 32, 48, 64 bytes).
bool parse_frame(std::string_view text, CanFrame* out);

}  // namespace curio::hal
