#pragma once
// An RGBA float image as the renderer produces it: linear light, premultiplied
// alpha, row 0 at the top, 4 floats per pixel.
#include <cstddef>
#include <vector>

namespace cutaway {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgba; ///< width * height * 4
    /// Optional, width * height: which proxy each pixel's first visible sample
    /// came from: operator index (0-based), -1 the untouched volume, -2 nothing.
    std::vector<float> operatorIds;

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0.0f) {}
    float* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
    const float* pixel(int x, int y) const {
        return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
    }
};

} // namespace cutaway
