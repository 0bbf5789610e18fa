#include "render/classify/preintegration.hpp"

#include <algorithm>
#include <cmath>
#include <system_error>
#include <thread>

namespace cutaway::render {
namespace {

struct Medium {
    glm::vec3 colour;
    double extinction; ///< per mm
};

} // namespace

std::vector<glm::vec4> preintegrate(const std::vector<glm::vec4>& table, double referenceMm,
                                    double segmentMm, int n, unsigned threads) {
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

    // Entries up to i with any extinction: a segment whose sub-steps only
    // interpolate between clear entries adds nothing (each of its sub-steps
    // would leave the colour and the transmittance exactly as they were).
    std::vector<int> opaqueUpTo(static_cast<std::size_t>(n) + 1, 0);
    for (int i = 0; i < n; ++i)
        opaqueUpTo[std::size_t(i) + 1] =
            opaqueUpTo[std::size_t(i)] + (media[std::size_t(i)].extinction > 0.0);

    std::vector<glm::vec4> out(static_cast<std::size_t>(n) * n);
    // Rows of back values, interleaved over the threads (a row's cost grows
    // with its distance from the diagonal, so interleaving balances them).
    // Each entry is computed alone, so the table is the same for any count.
    auto rows = [&](int first, int stride) {
        for (int b = first; b < n; b += stride)
            for (int f = 0; f < n; ++f) {
                // The sub-steps read entries min(f, b) to max(f, b), and the
                // next one with weight 0 when f == b: lo to hi.
                const int lo = std::min(f, b), hi = std::min(std::max(f, b) + 1, n - 1);
                if (opaqueUpTo[std::size_t(hi) + 1] == opaqueUpTo[std::size_t(lo)]) continue;
                // One sub-step per table entry crossed (at least 2) resolves every
                // feature of the transfer function along the segment.
                const int steps = std::max(2, std::abs(b - f) + 1);
                const double h = segmentMm / steps;
                double transmittance = 1.0;
                glm::dvec3 colour(0.0);
                for (int k = 0; k < steps; ++k) {
                    const double s = f + (b - f) * (k + 0.5) / steps;
                    const Medium m = at(s);
                    if (m.extinction == 0.0) continue; // as it would leave them
                    const double a = -std::expm1(-m.extinction * h);
                    colour += transmittance * a * glm::dvec3(m.colour);
                    transmittance *= 1.0 - a;
                }
                out[static_cast<std::size_t>(b) * n + f] =
                    glm::vec4(glm::vec3(colour), 1.0 - transmittance);
            }
    };
    if (threads == 0) threads = std::thread::hardware_concurrency();
    const int count = std::clamp(static_cast<int>(threads), 1, std::min(n, 64));
    std::vector<std::jthread> helpers;
    int started = 1; // this thread takes the rows of stride 0
    try {
        for (; started < count; ++started)
            helpers.emplace_back(rows, started, count);
    } catch (const std::system_error&) {
        // No more threads: this one takes the rest.
    }
    rows(0, count);
    for (int t = started; t < count; ++t)
        rows(t, count);
    helpers.clear(); // joins them before `out` is returned
    return out;
}

} // namespace cutaway::render
