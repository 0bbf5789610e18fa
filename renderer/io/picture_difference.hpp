#pragma once
// How far apart two renders of one picture look: the measure of picture
// quality the gallery's figures are held to (docs/quality.md). Both images'
// linear RGB, clipped to [0, 1], is encoded with gamma 1/2.2, as a display
// shows it, and compared over the whole image.
#include "io/image.hpp"

#include <cstddef>
#include <vector>

namespace cutaway {

struct PictureDifference {
    /// 10 log10(1 / mean squared error) over every pixel's R, G and B in the
    /// encoded values; infinite when the images are the same.
    double psnr = 0.0;
    /// The share of pixels (0..1) whose largest channel error exceeds
    /// `visibleStep` (by default 4/255: a step a reader sees in a print).
    double shareOff = 0.0;
    /// The largest channel error of any pixel, encoded.
    double maxError = 0.0;
    /// How many pixels were compared.
    std::size_t pixels = 0;
};

/// `a` against `b` (same size; throws std::invalid_argument otherwise).
PictureDifference comparePictures(const Image& a, const Image& b, double visibleStep = 4.0 / 255.0);

/// The same over the pixels `mask` holds (width * height, row by row) only.
PictureDifference comparePictures(const Image& a, const Image& b, const std::vector<bool>& mask,
                                  double visibleStep = 4.0 / 255.0);

/// The pixels of `image` whose alpha is `opaque` or more and whose every
/// neighbour within `erode` pixels (a square) is too: an opaque surface
/// without its silhouette, where a reconstruction's figures are read.
std::vector<bool> opaqueInterior(const Image& image, int erode, float opaque = 0.99f);

} // namespace cutaway
