// The cubic filter of shaders/shared/cubic_filter.h on the CPU twin of the
// shaders' code (sample_common.h's volumeAt: Catmull-Rom over the 4^3 texels
// around a sample, clamped to the edge as a sampler clamps, held to the
// range of the sample's cell). It passes through the texels, reproduces a
// linear ramp and a quadratic exactly away from the two texels at each
// border, and never leaves its cell's range. Controls: weights taken half a
// texel off break the ramp; trilinear filtering misses the quadratic by up
// to a / 4 (a x^2, x in texels).
#include "shared/cubic_filter.h"

#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <vector>

namespace cutaway::test {
namespace {

using shader::CubicCell;
using shader::ivec3;
using shader::vec3;
using shader::vec4;

struct Grid {
    ivec3 dims;
    std::vector<float> v;
    float at(ivec3 p) const {
        p = glm::clamp(p, ivec3(0), dims - 1); // clamp to edge
        return v[std::size_t(p.x + dims.x * (p.y + dims.y * p.z))];
    }
};

Grid gridOf(ivec3 dims, const std::function<float(vec3)>& f) {
    Grid g{dims, {}};
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                g.v.push_back(f(vec3(x, y, z)));
    return g;
}

// A sampler's trilinear, clamped-to-edge fetch at texture coordinate tc.
float linearAt(const Grid& g, vec3 tc) {
    const vec3 x = tc * vec3(g.dims) - 0.5f;
    const vec3 i = glm::floor(x), t = x - i;
    const ivec3 lo(i);
    float sum = 0.0f;
    for (int c = 0; c < 8; ++c) {
        const ivec3 d((c & 1) != 0, (c & 2) != 0, (c & 4) != 0);
        const vec3 w = glm::mix(1.0f - t, t, vec3(d));
        sum += w.x * w.y * w.z * g.at(lo + d);
    }
    return sum;
}

// The cubic as volumeAt takes it.
float cubicAt(const Grid& g, vec3 tc) {
    const CubicCell c = shader::cubicCell(tc, g.dims);
    float sum = 0.0f, lo = 1e30f, hi = -1e30f;
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) {
                const float v = g.at(ivec3(c.ix[x], c.iy[y], c.iz[z]));
                sum += c.wx[x] * c.wy[y] * c.wz[z] * v;
                if (shader::inCubicCell(x, y, z)) {
                    lo = std::min(lo, v);
                    hi = std::max(hi, v);
                }
            }
    return std::clamp(sum, lo, hi);
}

// Texture coordinates of points at texel-space positions spread over
// [from, to] on each axis, off the texel centres and the cells' middles.
std::vector<vec3> points(ivec3 dims, float from, float to) {
    std::vector<vec3> out;
    for (int i = 0; i <= 40; ++i) {
        const float s = from + (to - from) * (float(i) + 0.137f) / 40.5f;
        out.push_back(vec3(s, from + to - s, 0.5f * (from + to) + 0.3f * (s - from)) / vec3(dims));
    }
    return out;
}

TEST(CubicFilter, PassesThroughTheTexelsAndStaysInItsCell) {
    const Grid g = gridOf(ivec3(9, 7, 6), [](vec3 p) {
        return std::sin(1.3f * p.x) + std::cos(0.7f * p.y * p.z) + 0.1f * p.x * p.y;
    });
    // At a texel's centre, the texel (every texel, border ones too).
    for (int z = 0; z < 6; ++z)
        for (int y = 0; y < 7; ++y)
            for (int x = 0; x < 9; ++x)
                EXPECT_NEAR(cubicAt(g, (vec3(x, y, z) + 0.5f) / vec3(g.dims)), g.at(ivec3(x, y, z)),
                            1e-5f);
    // Elsewhere, within the range of the cell's eight texels, as trilinear
    // filtering is (and beyond the border, where clamping decides).
    for (const vec3 tc : points(g.dims, -1.0f, 10.0f)) {
        const ivec3 lo(glm::floor(tc * vec3(g.dims) - 0.5f));
        float cellLo = 1e30f, cellHi = -1e30f;
        for (int c = 0; c < 8; ++c) {
            const float v = g.at(lo + ivec3((c & 1) != 0, (c & 2) != 0, (c & 4) != 0));
            cellLo = std::min(cellLo, v);
            cellHi = std::max(cellHi, v);
        }
        EXPECT_GE(cubicAt(g, tc), cellLo);
        EXPECT_LE(cubicAt(g, tc), cellHi);
    }
    // The weights sum to 1.
    for (float t = 0.0f; t < 1.0f; t += 0.03125f) {
        const vec4 w = shader::catmullRomWeights(t);
        EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-6f);
    }
}

TEST(CubicFilter, ReproducesARampAwayFromTheBorder) {
    const ivec3 dims(16, 16, 16);
    const auto ramp = [](vec3 p) { return 0.3f * p.x - 0.2f * p.y + 0.05f * p.z + 1.0f; };
    const Grid g = gridOf(dims, ramp);
    // Texel-space positions 2 .. 14: the sample reads texels 0 .. 15.
    double worst = 0.0, control = 0.0;
    for (const vec3 tc : points(dims, 2.0f, 14.0f)) {
        const float exact = ramp(tc * vec3(dims) - 0.5f);
        worst = std::max(worst, double(std::abs(cubicAt(g, tc) - exact)));
        // Control: the sample half a texel off, as a sign slip would place it.
        control = std::max(control, double(std::abs(cubicAt(g, tc + 0.5f / vec3(dims)) - exact)));
    }
    EXPECT_LT(worst, 2e-5);
    EXPECT_GT(control, 0.05); // 0.5 * (0.3 - 0.2 + 0.05)
}

TEST(CubicFilter, ReproducesAQuadraticAwayFromTheBorder) {
    const ivec3 dims(24, 4, 4);
    const float a = 0.01f;
    // Its vertex off the grid's interior: within a cell holding a minimum,
    // the hold to the cell's range would lift it.
    const auto quadratic = [&](vec3 p) { return a * (p.x + 3.0f) * (p.x + 3.0f); };
    const Grid g = gridOf(dims, quadratic);
    // Along x, texel-space 2 .. 22. Trilinear = f + a t (1 - t), from 0 at
    // the texels to a / 4 between.
    double cubicWorst = 0.0, linearWorst = 0.0;
    for (int i = 0; i <= 200; ++i) {
        const float x = 1.5f + 20.0f * float(i) / 200.0f;
        const vec3 tc = vec3(x + 0.5f, 2.0f, 2.0f) / vec3(dims);
        const float f = quadratic(vec3(x, 0.0f, 0.0f));
        cubicWorst = std::max(cubicWorst, double(std::abs(cubicAt(g, tc) - f)));
        linearWorst = std::max(linearWorst, double(std::abs(linearAt(g, tc) - f)));
    }
    EXPECT_LT(cubicWorst, 2e-5); // float rounding of values up to 6.8
    // Control: trilinear filtering misses by a / 4 between texels.
    EXPECT_NEAR(linearWorst, a / 4.0, 2e-5);
}

} // namespace
} // namespace cutaway::test
