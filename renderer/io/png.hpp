#pragma once
// An 8-bit sRGB PNG preview of a linear premultiplied image, written with zlib
// (no libpng). Colour is un-premultiplied and sRGB-encoded; alpha is kept, so a
// transparent background stays transparent. Written atomically.
#include "io/image.hpp"

#include <filesystem>

namespace cutaway {

void writePng(const std::filesystem::path& path, const Image& image);

/// Linear [0,1] -> sRGB-encoded [0,1] (IEC 61966-2-1 curve). Inputs outside [0,1]
/// are clamped first; NaN gives 0.
float linearToSrgb(float linear);

} // namespace cutaway
