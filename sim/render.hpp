// The 64×64 RGB observation of SPEC §1.4: black background, yellow ball (radius 0.17)
// drawn first, blue distractor (radius 0.15) on top, anti-aliased by exact pixel
// coverage; world (x, y) → pixel column u = 32 + 32x, row v = 32 + 32y, where pixel
// (row, col) is the unit square [col, col+1] × [row, row+1] (cairo's convention): the
// world origin lies on the corner shared by pixels 31 and 32.
#pragma once
#include <array>
#include <cstdint>
#include <string>

#include "sim/world.hpp"

namespace curio::sim {

// The renderer's version: raised whenever the image of a scene changes (tests/sim/test_render.cpp
// pins the images of version 1 by their hash). It is part of the simulated world's identity
// (sim/world_identity.hpp): a learned goal space sees the world through it.
inline constexpr uint32_t kRendererVersion = 1;

inline constexpr int kImageSize = 64;
inline constexpr int kImageChannels = 3;
inline constexpr int kImageValues = kImageSize * kImageSize * kImageChannels;

// HWC, row-major (row 0 at the top), values in [0, 1].
using Image = std::array<float, kImageValues>;

void render_scene(const Vec2& ball, const Vec2& distractor, Image* out);

// The same scene at width × height (HWC floats, `hwc` holds width·height·3), square pixels, the
// world's origin at the centre and min(width, height)/2 pixels per world unit: the field of view
// of the 64×64 image, widened on the longer side (a 4:3 camera sees [-4/3, 4/3] × [-1, 1]).
// 64×64 gives render_scene's image bit for bit. The discs must span ≤ 64 pixels:
// min(width, height) ≤ kMaxRenderSide.
inline constexpr int kMaxRenderSide = 320;
void render_scene(const Vec2& ball, const Vec2& distractor, int width, int height, float* hwc);

// 8-bit RGB PNG of an HWC image (values clamped to [0,1]). Returns false with a
// message in *error on failure.
bool write_png(const std::string& path, const float* hwc, int width, int height,
               std::string* error);

}  // namespace curio::sim
