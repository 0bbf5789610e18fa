#include "io/picture_difference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cutaway {
namespace {

double encoded(float linear) {
    const double clipped = std::clamp(static_cast<double>(linear), 0.0, 1.0);
    return std::pow(clipped, 1.0 / 2.2);
}

} // namespace

PictureDifference comparePictures(const Image& a, const Image& b, double visibleStep) {
    if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
        throw std::invalid_argument("comparePictures: the images differ in size");
    PictureDifference d;
    double squared = 0.0;
    std::size_t off = 0;
    const std::size_t pixels = a.rgba.size() / 4;
    for (std::size_t p = 0; p < pixels; ++p) {
        double largest = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double e = std::abs(encoded(a.rgba[4 * p + c]) - encoded(b.rgba[4 * p + c]));
            squared += e * e;
            largest = std::max(largest, e);
        }
        off += largest > visibleStep ? 1 : 0;
        d.maxError = std::max(d.maxError, largest);
    }
    const double mse = pixels ? squared / (3.0 * double(pixels)) : 0.0;
    d.psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
    d.shareOff = pixels ? double(off) / double(pixels) : 0.0;
    return d;
}

} // namespace cutaway
