#pragma once
// A test volume for segment alignment: tissue (value 100) over bone (200)
// whose top is a plane tilted 12 and 8 degrees across the grid, so the
// bone's voxels meet the tissue in a staircase while the values, ramping
// from 200 to 100 over one voxel across the plane as a scan's partial volume
// does, describe a smooth surface. Tissue lies below z = 8 mm over
// |x|, |y| < 30 mm (the volume centred on the origin); air (0) elsewhere.
#include "volume/volume.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>

namespace cutaway::test {

inline Volume tissueOverTiltedBone(int voxels, double spacing) {
    Volume v = Volume::allocate(glm::ivec3(voxels), VoxelType::U8, glm::dvec3(spacing));
    const double a = std::tan(12.0 * std::numbers::pi / 180.0);
    const double b = std::tan(8.0 * std::numbers::pi / 180.0);
    const double norm = std::sqrt(1.0 + a * a + b * b);
    for (int z = 0; z < voxels; ++z)
        for (int y = 0; y < voxels; ++y)
            for (int x = 0; x < voxels; ++x) {
                const glm::dvec3 p = (glm::dvec3(x, y, z) + 0.5 - 0.5 * voxels) * spacing;
                if (std::abs(p.x) >= 30 || std::abs(p.y) >= 30 || p.z >= 8) continue;
                const double above = (p.z - (-2.0 + a * p.x + b * p.y)) / norm / spacing;
                const double value = 100.0 + 100.0 * std::clamp(0.5 - above, 0.0, 1.0);
                v.data[v.index(x, y, z)] = std::byte(static_cast<uint8_t>(std::lround(value)));
            }
    return v;
}

// The bone (values from 150) as label 1, the rest 0.
inline Volume tiltedBoneLabels(const Volume& values) {
    Volume labels = Volume::allocate(values.dims, VoxelType::U8, values.spacing);
    for (std::size_t i = 0; i < labels.data.size(); ++i)
        labels.data[i] = std::byte(std::to_integer<int>(values.data[i]) >= 150 ? 1 : 0);
    return labels;
}

// A peeler keeping the bone (a segment by value range) that lifts the
// tissue over |x| < 25, |y| < 20 from x = -15 on and stands it upright there:
// the flap's thickness across it is the tissue's over the tilted plane.
inline nlohmann::json standingFlapPeeler() {
    return {{"type", "peeler"},
            {"placement", {{"translate", {0, 0, 0}}, {"scale", {50, 40, 16}}}},
            {"params", {{"hinge", -15}, {"thickness", 15}, {"radius", 3}, {"angle", 90}}},
            {"alignment", {{"mode", "segment"}, {"range", {150, 255}}, {"band", 2}}}};
}

// Solves the n x n system a x = b (Gaussian elimination, partial pivoting).
template <std::size_t N>
inline std::array<double, N> solve(std::array<std::array<double, N>, N> a,
                                   std::array<double, N> b) {
    for (std::size_t c = 0; c < N; ++c) {
        std::size_t pivot = c;
        for (std::size_t r = c + 1; r < N; ++r)
            if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
        std::swap(a[c], a[pivot]);
        std::swap(b[c], b[pivot]);
        for (std::size_t r = c + 1; r < N; ++r) {
            const double f = a[r][c] / a[c][c];
            for (std::size_t k = c; k < N; ++k)
                a[r][k] -= f * a[c][k];
            b[r] -= f * b[c];
        }
    }
    std::array<double, N> x{};
    for (std::size_t c = N; c-- > 0;) {
        double s = b[c];
        for (std::size_t k = c + 1; k < N; ++k)
            s -= a[c][k] * x[k];
        x[c] = s / a[c][c];
    }
    return x;
}

struct FitSample {
    double u = 0.0, v = 0.0, value = 0.0;
};

// The RMS residual of `samples` about the quadratic in (u, v) that fits them
// best (least squares).
inline double quadraticResidualRms(const std::vector<FitSample>& samples) {
    constexpr std::size_t kTerms = 6;
    const auto terms = [](const FitSample& s) {
        return std::array<double, kTerms>{1.0, s.u, s.v, s.u * s.u, s.u * s.v, s.v * s.v};
    };
    std::array<std::array<double, kTerms>, kTerms> normal{};
    std::array<double, kTerms> rhs{};
    for (const FitSample& s : samples) {
        const std::array<double, kTerms> t = terms(s);
        for (std::size_t i = 0; i < kTerms; ++i) {
            for (std::size_t j = 0; j < kTerms; ++j)
                normal[i][j] += t[i] * t[j];
            rhs[i] += t[i] * s.value;
        }
    }
    const std::array<double, kTerms> fit = solve(normal, rhs);
    double sum = 0.0;
    for (const FitSample& s : samples) {
        const std::array<double, kTerms> t = terms(s);
        double predicted = 0.0;
        for (std::size_t i = 0; i < kTerms; ++i)
            predicted += fit[i] * t[i];
        sum += (s.value - predicted) * (s.value - predicted);
    }
    return samples.empty() ? 0.0 : std::sqrt(sum / double(samples.size()));
}

} // namespace cutaway::test
