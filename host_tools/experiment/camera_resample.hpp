// A camera image of any size as the encoder's 64×64 frame: per axis, an area average (box
// filter) when shrinking and linear interpolation between pixel centres when enlarging, each
// output byte rounded. One implementation for `curio-encode --resize` (a user's PNGs) and
// `curio-controller --camera` (a camera on the controller's computer), so both see the same
// frame for the same image.
#pragma once
#include <cstdint>

namespace curio::lab {

// rgb: width × height × 3 bytes, HWC, row 0 at the top (1 ≤ width, height); frame: 64×64×3.
void resample_to_camera(const uint8_t* rgb, int width, int height, uint8_t* frame);

}  // namespace curio::lab
