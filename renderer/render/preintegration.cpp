#include "render/preintegration.hpp"

#include <algorithm>
#include <cmath>

namespace cutaway::render {
namespace {

struct Medium {
    glm::vec3 colour;
    double extinction; ///< per mm
};

} // namespace

std::vector<glm::vec4> preintegrate(const std::vector<glm::vec4>& table, double referenceMm,
                                    double segmentMm, int n) {
    // Resample the transfer function to n entries of colour and extinction
    // coefficient tau = -ln(1 - alpha) / reference length.
    std::vector<Medium> media(static_cast<std::size_t>(n));
    const double last = static_cast<double>(table.size() - 1);
    for (int i = 0; i < n; ++i) {
        const double x = last * i / (n - 1);
        const std::size_t i0 = static_cast<std::size_t>(x);
        const std::size_t i1 = std::min(i0 + 1, table.size() - 1);
        const glm::vec4 v = glm::mix(table[i0], table[i1], static_cast<float>(x - double(i0)));
        const double alpha = std::clamp(static_cast<double>(v.w), 0.0, 0.999999);
        media[static_cast<std::size_t>(i)] = {glm::vec3(v), -std::log1p(-alpha) / referenceMm};
    }
    auto at = [&](double s) { // linear interpolation at a fractional index
        const std::size_t i0 = static_cast<std::size_t>(s);
        const std::size_t i1 = std::min<std::size_t>(i0 + 1, media.size() - 1);
        const double t = s - static_cast<double>(i0);
        return Medium{glm::mix(media[i0].colour, media[i1].colour, static_cast<float>(t)),
                      media[i0].extinction * (1.0 - t) + media[i1].extinction * t};
    };

    std::vector<glm::vec4> out(static_cast<std::size_t>(n) * n);
    for (int b = 0; b < n; ++b)
        for (int f = 0; f < n; ++f) {
            // One sub-step per table entry crossed (at least 2) resolves every
            // feature of the transfer function along the segment.
            const int steps = std::max(2, std::abs(b - f) + 1);
            const double h = segmentMm / steps;
            double transmittance = 1.0;
            glm::dvec3 colour(0.0);
            for (int k = 0; k < steps; ++k) {
                const double s = f + (b - f) * (k + 0.5) / steps;
                const Medium m = at(s);
                const double a = -std::expm1(-m.extinction * h);
                colour += transmittance * a * glm::dvec3(m.colour);
                transmittance *= 1.0 - a;
            }
            out[static_cast<std::size_t>(b) * n + f] =
                glm::vec4(glm::vec3(colour), 1.0 - transmittance);
        }
    return out;
}

} // namespace cutaway::render
