#include "volume_info.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace cutaway::cli {

std::string describeVolume(const Volume& volume, const std::string& name) {
    char line[256];
    std::string out;
    auto add = [&](const char* fmt, auto... args) {
        std::snprintf(line, sizeof line, fmt, args...);
        out += line;
    };
    const ValueRange range = valueRange(volume);
    add("%s\n", name.c_str());
    add("  dims     %d x %d x %d (%zu voxels)\n", volume.dims.x, volume.dims.y, volume.dims.z,
        volume.voxelCount());
    add("  type     %s\n", std::string(voxelTypeName(volume.type)).c_str());
    add("  spacing  %g x %g x %g mm\n", volume.spacing.x, volume.spacing.y, volume.spacing.z);
    const glm::dvec3 e = volume.extent();
    add("  extent   %g x %g x %g mm\n", e.x, e.y, e.z);
    if (volume.hasPhysicalPlacement()) {
        // Where `cutaway export` places its grid; the render uses index axes.
        const char* space = volume.space == Space::LPS    ? "LPS"
                            : volume.space == Space::None ? "none given"
                                                          : "not anatomical";
        add("  space    %s\n", space);
        add("  origin   (%g, %g, %g) mm, the centre of voxel (0, 0, 0)\n", volume.origin.x,
            volume.origin.y, volume.origin.z);
        for (int a = 0; a < 3; ++a) {
            glm::dvec3 d = volume.direction[a];
            for (int c = 0; c < 3; ++c) // single-precision noise (1e-9) and -0 as 0
                d[c] = std::abs(d[c]) < 1e-6 ? 0.0 : d[c];
            add("  axis %c   along (%.4g, %.4g, %.4g)\n", "ijk"[a], d.x, d.y, d.z);
        }
    }
    if (volume.slope != 1.0 || volume.inter != 0.0)
        add("  scaling  value = raw * %g + %g\n", volume.slope, volume.inter);
    add("  values   [%g, %g]\n", range.min, range.max);
    // NaN and infinite voxels are left out of the values (and rendered as empty).
    if (const std::size_t count = nonFiniteCount(volume))
        add("  non-finite %zu voxel(s) (NaN or infinite): not in the values or the histogram\n",
            count);

    constexpr int kBins = 16;
    std::vector<std::size_t> bins(kBins, 0);
    const double width = range.max > range.min ? (range.max - range.min) / kBins : 1.0;
    for (std::size_t i = 0; i < volume.voxelCount(); ++i) {
        const double v = volume.value(i);
        if (!std::isfinite(v)) continue;
        int b = static_cast<int>((v - range.min) / width);
        bins[static_cast<std::size_t>(std::clamp(b, 0, kBins - 1))]++;
    }
    const std::size_t peak = std::max<std::size_t>(1, *std::max_element(bins.begin(), bins.end()));
    add("  histogram (%d bins, %% of voxels)\n", kBins);
    for (int b = 0; b < kBins; ++b) {
        const std::size_t n = bins[static_cast<std::size_t>(b)];
        const int bar = static_cast<int>(40.0 * static_cast<double>(n) / static_cast<double>(peak));
        add("    [%10.4g, %10.4g) %6.2f%% %s\n", range.min + b * width, range.min + (b + 1) * width,
            100.0 * static_cast<double>(n) / static_cast<double>(volume.voxelCount()),
            std::string(static_cast<std::size_t>(bar), '#').c_str());
    }
    return out;
}

} // namespace cutaway::cli
