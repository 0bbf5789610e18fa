#pragma once
// An RGBA float image as the renderer produces it: linear light, premultiplied
// alpha, row 0 at the top, 4 floats per pixel.
#include <cstddef>
#include <string>
#include <vector>

namespace cutaway {

/// A named float channel of an Image, width * height values.
struct ImageChannel {
    std::string name;
    std::vector<float> values;
};

struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgba; ///< width * height * 4
    /// Optional, width * height: which proxy each pixel's first visible sample
    /// came from: operator index (0-based), -1 the untouched volume, -2 nothing.
    std::vector<float> operatorIds;
    /// Optional, width * height: the planar depth in mm (along the view axis,
    /// from the eye's plane) of the first visible sample, or of a mesh where
    /// one is nearer; +infinity where nothing is visible (the EXR channel "Z").
    std::vector<float> depth;
    /// Optional, width * height: the label id of the first visible sample, 0
    /// where none is (the EXR channel "label").
    std::vector<float> labelIds;
    /// Optional: per matte, its channel's name and width * height shares of
    /// each pixel's colour that samples of the matte's label gave, in
    /// [0, alpha].
    std::vector<ImageChannel> mattes;

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0.0f) {}
    float* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
    const float* pixel(int x, int y) const {
        return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
    }
};

} // namespace cutaway
