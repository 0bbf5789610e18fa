#include "volume/otsu.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace cutaway {

double otsuThreshold(const Volume& volume) {
    constexpr int kBins = 256;
    const ValueRange range = valueRange(volume);
    if (!(range.max > range.min)) return range.min;
    const double width = (range.max - range.min) / kBins;

    std::array<double, kBins> histogram{};
    const std::size_t n = volume.voxelCount();
    for (std::size_t i = 0; i < n; ++i) {
        const double v = volume.value(i);
        if (!std::isfinite(v)) continue;
        const int bin = std::clamp(static_cast<int>((v - range.min) / width), 0, kBins - 1);
        histogram[std::size_t(bin)] += 1.0;
    }
    double total = 0.0, totalMoment = 0.0;
    for (int b = 0; b < kBins; ++b) {
        total += histogram[std::size_t(b)];
        totalMoment += b * histogram[std::size_t(b)];
    }

    // Split after bin k: class 0 = bins [0, k], class 1 = bins (k, 255].
    std::array<double, kBins - 1> between{};
    double count0 = 0.0, moment0 = 0.0, best = -1.0;
    for (int k = 0; k < kBins - 1; ++k) {
        count0 += histogram[std::size_t(k)];
        moment0 += k * histogram[std::size_t(k)];
        const double count1 = total - count0;
        if (count0 > 0.0 && count1 > 0.0) {
            const double mean0 = moment0 / count0;
            const double mean1 = (totalMoment - moment0) / count1;
            between[std::size_t(k)] = count0 * count1 * (mean0 - mean1) * (mean0 - mean1);
        }
        best = std::max(best, between[std::size_t(k)]);
    }
    // The middle of the best splits (a plateau when bins between the classes are empty).
    int first = -1, last = -1;
    for (int k = 0; k < kBins - 1; ++k)
        if (between[std::size_t(k)] >= best * (1.0 - 1e-12)) {
            if (first < 0) first = k;
            last = k;
        }
    const double split = 0.5 * (first + last) + 1.0; // bins below the split
    return range.min + split * width;
}

} // namespace cutaway
