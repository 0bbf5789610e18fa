#pragma once
// An 8-bit sRGB PNG preview of a linear premultiplied image, written with
// libpng. Colour is un-premultiplied and sRGB-encoded; alpha is kept, so a
// transparent background stays transparent. Written atomically.
#include "io/image.hpp"

#include <cstdint>
#include <filesystem>

namespace cutaway {

void writePng(const std::filesystem::path& path, const Image& image);

/// Linear [0,1] -> sRGB-encoded [0,1] (IEC 61966-2-1 curve). Inputs outside [0,1]
/// are clamped first; NaN gives 0.
float linearToSrgb(float linear);

/// The 8-bit sRGB code of a linear value: linearToSrgb(linear) * 255 rounded to
/// nearest, 0 for NaN; as exact as computing it, several times faster.
std::uint8_t linearToSrgbByte(float linear);

} // namespace cutaway
