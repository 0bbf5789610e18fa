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

PictureDifference compare(const Image& a, const Image& b, const std::vector<bool>* mask,
                          double visibleStep) {
    if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
        throw std::invalid_argument("comparePictures: the images differ in size");
    if (mask && mask->size() != a.rgba.size() / 4)
        throw std::invalid_argument("comparePictures: the mask differs in size");
    PictureDifference d;
    double squared = 0.0;
    std::size_t off = 0, pixels = 0;
    for (std::size_t p = 0; p < a.rgba.size() / 4; ++p) {
        if (mask && !(*mask)[p]) continue;
        ++pixels;
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
    d.pixels = pixels;
    return d;
}

} // namespace

PictureDifference comparePictures(const Image& a, const Image& b, double visibleStep) {
    return compare(a, b, nullptr, visibleStep);
}

PictureDifference comparePictures(const Image& a, const Image& b, const std::vector<bool>& mask,
                                  double visibleStep) {
    return compare(a, b, &mask, visibleStep);
}

std::vector<bool> opaqueInterior(const Image& image, int erode, float opaque) {
    const int w = image.width, h = image.height;
    auto solid = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < w && y < h &&
               image.rgba[4 * (std::size_t(y) * std::size_t(w) + std::size_t(x)) + 3] >= opaque;
    };
    std::vector<bool> mask(std::size_t(w) * std::size_t(h), false);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool inside = true;
            for (int dy = -erode; dy <= erode && inside; ++dy)
                for (int dx = -erode; dx <= erode && inside; ++dx)
                    inside = solid(x + dx, y + dy);
            mask[std::size_t(y) * std::size_t(w) + std::size_t(x)] = inside;
        }
    return mask;
}

} // namespace cutaway
