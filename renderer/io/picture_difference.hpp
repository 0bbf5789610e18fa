#pragma once
// How far apart two renders of one picture look: the measure of picture
// quality the gallery's figures are held to (docs/quality.md). Both images'
// linear RGB, clipped to [0, 1], is encoded with gamma 1/2.2, as a display
// shows it, and compared over the whole image.
#include "io/image.hpp"

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
};

/// `a` against `b` (same size; throws std::invalid_argument otherwise).
PictureDifference comparePictures(const Image& a, const Image& b, double visibleStep = 4.0 / 255.0);

} // namespace cutaway
