// The feature-alignment bakes (paper sections 4.2, 4.3) against independent
// CPU references: the distance field against a brute-force Euclidean
// distance transform, the segment mask against its CPU twin, plus the
// properties the renderer relies on (gradients point into the feature,
// M >= 0.5 exactly at the segment's voxels).
#include "bake/feature_bake.hpp"
#include "bake/volume_upload.hpp"
#include "core/error.hpp"
#include "gpu_fixture.hpp"
#include "shared/feature.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <limits>
#include <random>

namespace cutaway::test {
namespace {

std::size_t indexOf(glm::ivec3 d, int x, int y, int z) {
    return std::size_t(x) + std::size_t(d.x) * (std::size_t(y) + std::size_t(d.y) * std::size_t(z));
}

/// Random object mask: each voxel is background with probability `background`.
std::vector<uint8_t> randomMask(glm::ivec3 dims, double background, unsigned seed) {
    std::mt19937 rng(seed);
    std::bernoulli_distribution isBackground(background);
    std::vector<uint8_t> mask(std::size_t(dims.x) * dims.y * dims.z);
    for (auto& m : mask)
        m = isBackground(rng) ? 0 : 1;
    return mask;
}

/// A ball of object voxels (radius in mm) around the grid's centre.
std::vector<uint8_t> ballMask(glm::ivec3 dims, glm::dvec3 spacing, double radiusMm) {
    std::vector<uint8_t> mask(std::size_t(dims.x) * dims.y * dims.z);
    const glm::dvec3 centre = glm::dvec3(dims - 1) * 0.5 * spacing;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                mask[indexOf(dims, x, y, z)] =
                    glm::length(glm::dvec3(x, y, z) * spacing - centre) <= radiusMm ? 1 : 0;
    return mask;
}

/// The definition itself: for every voxel the smallest distance in mm to any
/// background voxel centre (O(voxels x background voxels)); 65504 without background.
std::vector<double> bruteForceDistance(const std::vector<uint8_t>& object, glm::ivec3 dims,
                                       glm::dvec3 spacing) {
    std::vector<glm::dvec3> background;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                if (!object[indexOf(dims, x, y, z)])
                    background.push_back(glm::dvec3(x, y, z) * spacing);
    std::vector<double> out(object.size(), 65504.0);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const glm::dvec3 p = glm::dvec3(x, y, z) * spacing;
                double best = std::numeric_limits<double>::infinity();
                for (const glm::dvec3& b : background) {
                    const glm::dvec3 d = p - b;
                    best = std::min(best, glm::dot(d, d));
                }
                if (!background.empty()) out[indexOf(dims, x, y, z)] = std::sqrt(best);
            }
    return out;
}

/// Uploads an object mask as a uint8 volume of 0 / 255 (window [0, 255]).
gpu::Image uploadMask(const gpu::Context& ctx, const std::vector<uint8_t>& object, glm::ivec3 dims,
                      glm::dvec3 spacing) {
    Volume v = Volume::allocate(dims, VoxelType::U8, spacing);
    for (std::size_t i = 0; i < object.size(); ++i)
        v.data[i] = std::byte(object[i] ? 255 : 0);
    return bake::uploadVolume(ctx, v, {0.0, 255.0});
}

/// The direction the operator shader takes from a baked field at a voxel
/// (featureDirection in glsl/slice_operator.h): featureGradientOf over its
/// neighbours, clamped to the grid.
glm::vec3 fieldDirection(const std::vector<float>& field, glm::ivec3 d, glm::dvec3 spacing, int x,
                         int y, int z) {
    auto at = [&](int i, int j, int k) {
        return field[indexOf(d, std::clamp(i, 0, d.x - 1), std::clamp(j, 0, d.y - 1),
                             std::clamp(k, 0, d.z - 1))];
    };
    const glm::vec3 below(at(x - 1, y, z), at(x, y - 1, z), at(x, y, z - 1));
    const glm::vec3 above(at(x + 1, y, z), at(x, y + 1, z), at(x, y, z + 1));
    return shader::featureGradientOf(below, above, glm::vec3(0.5 / spacing));
}

struct DistanceCase {
    glm::ivec3 dims;
    double background; ///< probability of a background voxel
    unsigned seed;
};

/// Fixtures named for the bake they test (both are GpuTest: validation on).
class DistanceField : public GpuTest {};
class SegmentMask : public GpuTest {};

TEST_F(DistanceField, MatchesBruteForce) {
    const glm::dvec3 spacing(0.7, 1.3, 2.0); // anisotropic: a swapped axis would show
    const DistanceCase cases[] = {{{17, 23, 11}, 0.02, 1},
                                  {{17, 23, 11}, 0.5, 2},
                                  {{17, 23, 11}, 0.002, 3}, // most lines without background
                                  {{32, 32, 32}, 0.01, 4},
                                  {{32, 32, 32}, 0.3, 5}};
    bake::FeatureBaker baker(ctx());
    for (const DistanceCase& c : cases) {
        SCOPED_TRACE(testing::Message() << "seed " << c.seed);
        const std::vector<uint8_t> object = randomMask(c.dims, c.background, c.seed);
        const std::vector<double> exact = bruteForceDistance(object, c.dims, spacing);
        gpu::Image values = uploadMask(ctx(), object, c.dims, spacing);
        const std::vector<float> field =
            downloadFeatureField(ctx(), baker.distanceField(values, spacing, 0.5f));
        const std::vector<float> cpu = bake::distanceFieldCpu(object, c.dims, spacing);
        ASSERT_EQ(field.size(), exact.size());
        int gpuBad = 0, cpuBad = 0;
        for (std::size_t i = 0; i < exact.size(); ++i) {
            // Each of the GPU's three passes stores half floats, and Vulkan lets
            // a storage write round toward zero (lavapipe does): within 2^-10
            // relative each, so 3 * 2^-10 plus 1e-3 mm for the float arithmetic.
            if (std::abs(field[i] - exact[i]) > exact[i] * 3 * 0x1p-10 + 1e-3 && gpuBad++ < 5)
                ADD_FAILURE() << "voxel " << i << ": GPU " << field[i] << ", exact " << exact[i];
            if (std::abs(cpu[i] - exact[i]) > exact[i] * 1e-4 + 1e-6 && cpuBad++ < 5)
                ADD_FAILURE() << "voxel " << i << ": CPU " << cpu[i] << ", exact " << exact[i];
            if (!object[i]) {
                EXPECT_EQ(field[i], 0.0f);
            }
        }
        EXPECT_EQ(gpuBad, 0);
        EXPECT_EQ(cpuBad, 0);
    }
}

TEST_F(DistanceField, ThresholdsNormalizedValues) {
    // Values 0..255 along x; threshold 0.5 of the window: x >= 128 is object.
    const glm::ivec3 dims(24, 3, 2);
    const glm::dvec3 spacing(1.5, 1.0, 1.0);
    Volume v = Volume::allocate(dims, VoxelType::U8, spacing);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                v.data[v.index(x, y, z)] = std::byte(uint8_t(x * 11));
    bake::FeatureBaker baker(ctx());
    gpu::Image values = bake::uploadVolume(ctx(), v, {0.0, 255.0});
    const std::vector<float> field =
        downloadFeatureField(ctx(), baker.distanceField(values, spacing, 0.5f));
    for (int x = 0; x < dims.x; ++x) {
        const double expected = x * 11 > 127.5 ? (x - 11) * spacing.x : 0.0; // 11 * 11 = 121
        EXPECT_NEAR(field[v.index(x, 1, 1)], expected, expected * 0x1p-10 + 1e-3) << x;
    }
}

TEST_F(DistanceField, WithoutBackgroundIsLargeAndFlat) {
    const glm::ivec3 dims(5, 4, 3);
    const std::vector<uint8_t> object(60, 1);
    bake::FeatureBaker baker(ctx());
    gpu::Image values = uploadMask(ctx(), object, dims, glm::dvec3(1.0));
    const std::vector<float> field =
        downloadFeatureField(ctx(), baker.distanceField(values, glm::dvec3(1.0), 0.5f));
    for (float t : field)
        EXPECT_EQ(t, 65504.0f);
    EXPECT_EQ(fieldDirection(field, dims, glm::dvec3(1.0), 2, 2, 1), glm::vec3(0.0f));
    for (float d : bake::distanceFieldCpu(object, dims, glm::dvec3(1.0)))
        EXPECT_EQ(d, 65504.0f);
}

TEST_F(DistanceField, GradientPointsIntoTheObject) {
    const glm::ivec3 dims(30, 26, 20);
    const glm::dvec3 spacing(1.0, 1.2, 1.5);
    const std::vector<uint8_t> object = ballMask(dims, spacing, 12.0);
    const glm::dvec3 centre = glm::dvec3(dims - 1) * 0.5 * spacing;
    bake::FeatureBaker baker(ctx());
    gpu::Image values = uploadMask(ctx(), object, dims, spacing);
    const std::vector<float> field =
        downloadFeatureField(ctx(), baker.distanceField(values, spacing, 0.5f));
    int checked = 0;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const std::size_t i = indexOf(dims, x, y, z);
                const glm::dvec3 toCentre = centre - glm::dvec3(x, y, z) * spacing;
                if (!object[i] || glm::length(toCentre) < 3.0) continue;
                const glm::vec3 g = fieldDirection(field, dims, spacing, x, y, z);
                EXPECT_NEAR(glm::length(g), 1.0f, 2e-3f) << x << " " << y << " " << z;
                EXPECT_GT(glm::dot(glm::dvec3(g), glm::normalize(toCentre)), 0.5)
                    << x << " " << y << " " << z;
                ++checked;
            }
    EXPECT_GT(checked, 1000);
}

TEST_F(DistanceField, RefusesLinesLongerThan1024) {
    bake::FeatureBaker baker(ctx());
    Volume v = Volume::allocate({1025, 1, 1}, VoxelType::U8);
    gpu::Image values = bake::uploadVolume(ctx(), v, {0.0, 255.0});
    try {
        (void)baker.distanceField(values, glm::dvec3(1.0), 0.5f);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("1024"), std::string::npos) << e.what();
    }
}

TEST_F(SegmentMask, MatchesCpuTwin) {
    const glm::ivec3 dims(21, 17, 13);
    const glm::dvec3 spacing(0.8, 1.1, 1.7);
    bake::FeatureBaker baker(ctx());
    for (unsigned seed : {11u, 12u}) {
        // A ball with random holes, plus random specks outside: the segment has flat
        // parts, single voxels, and outside voxels where the smoothed indicator is > 0.5.
        std::vector<uint8_t> indicator = ballMask(dims, spacing, 7.0);
        const std::vector<uint8_t> flips = randomMask(dims, 0.05, seed);
        for (std::size_t i = 0; i < indicator.size(); ++i)
            indicator[i] = uint8_t((indicator[i] != 0) != (flips[i] == 0) ? 1 : 0);
        // Radii 1-6, 9-19 and capped at 32: every window of the blur (4, 8, 16, 32).
        for (double band : {0.0, 1.0, 3.0, 10.0, 40.0}) {
            SCOPED_TRACE(testing::Message() << "seed " << seed << " band " << band);
            const std::vector<float> field =
                downloadFeatureField(ctx(), baker.segmentMask(indicator, dims, spacing, band));
            const std::vector<float> cpu = bake::smoothMaskCpu(indicator, dims, spacing, band);
            ASSERT_EQ(field.size(), cpu.size());
            int bad = 0;
            for (std::size_t i = 0; i < cpu.size(); ++i) {
                // Half floats in [0, 1] are within 2^-12 of the float; 2e-3 covers exp().
                if (std::abs(field[i] - cpu[i]) > 2e-3f && bad++ < 5)
                    ADD_FAILURE() << "voxel " << i << ": GPU " << field[i] << ", CPU " << cpu[i];
                if (indicator[i]) {
                    EXPECT_GE(field[i], 0.5f);
                    EXPECT_GE(cpu[i], 0.5f);
                } else {
                    EXPECT_LT(field[i], 0.5f);
                    EXPECT_LT(cpu[i], 0.5f);
                }
                if (band == 0.0) {
                    EXPECT_EQ(field[i], indicator[i] ? 1.0f : 0.0f);
                }
            }
            EXPECT_EQ(bad, 0);
        }
    }
}

TEST(SegmentMaskCpu, SmoothsAcrossTheBoundaryWithTheBandWidthInMillimetres) {
    // A half space (the upper 20 voxels of 40) along each axis in turn: the smoothed
    // step is the normal CDF of sigma = band / 2 mm, i.e. 2 / spacing[axis] voxels.
    // The clamped borders extend the constant ends, so the model holds everywhere.
    const glm::dvec3 spacing(0.5, 0.8, 1.25);
    const double band = 4.0;
    for (int axis = 0; axis < 3; ++axis) {
        glm::ivec3 dims(1);
        dims[axis] = 40;
        std::vector<uint8_t> indicator(40, 0);
        for (int i = 20; i < 40; ++i)
            indicator[std::size_t(i)] = 1;
        const std::vector<float> m = bake::smoothMaskCpu(indicator, dims, spacing, band);
        const double sigmaVoxels = band / 2.0 / spacing[axis];
        for (int i = 0; i < 40; ++i) {
            const double cdf = 0.5 * std::erfc(-(i - 19.5) / (sigmaVoxels * std::sqrt(2.0)));
            const double encoded = i >= 20 ? std::max(cdf, 0.5) : std::min(cdf, 0.498);
            EXPECT_NEAR(m[std::size_t(i)], encoded, 0.01) << "axis " << axis << ", voxel " << i;
        }
    }
    const glm::ivec3 dims(20, 1, 1);
    const std::vector<uint8_t> indicator(20, 1);
    EXPECT_THROW(bake::smoothMaskCpu(indicator, dims, glm::dvec3(0.5), -1.0), InputError);
    EXPECT_THROW(bake::smoothMaskCpu(indicator, {19, 1, 1}, glm::dvec3(0.5), 1.0), InputError);
}

TEST_F(SegmentMask, GradientPointsIntoTheSegmentOnBothSides) {
    // The segment is the half space z >= 6 (a flat boundary between z = 5 and 6).
    const glm::ivec3 dims(8, 9, 12);
    const glm::dvec3 spacing(1.0, 0.9, 1.4);
    std::vector<uint8_t> indicator(std::size_t(dims.x) * dims.y * dims.z);
    for (int z = 6; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                indicator[indexOf(dims, x, y, z)] = 1;
    bake::FeatureBaker baker(ctx());
    for (double band : {0.0, 2.0}) {
        SCOPED_TRACE(testing::Message() << "band " << band);
        const std::vector<float> field =
            downloadFeatureField(ctx(), baker.segmentMask(indicator, dims, spacing, band));
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                EXPECT_LT(field[indexOf(dims, x, y, 5)], 0.5f); // outside
                EXPECT_GE(field[indexOf(dims, x, y, 6)], 0.5f); // inside
                for (int z : {5, 6}) {
                    const glm::vec3 g = fieldDirection(field, dims, spacing, x, y, z);
                    EXPECT_NEAR(glm::distance(g, glm::vec3(0, 0, 1)), 0.0f, 2e-3f) << z;
                }
                // Far from the boundary without smoothing the field is flat: no direction.
                if (band == 0.0) {
                    EXPECT_EQ(fieldDirection(field, dims, spacing, x, y, 1), glm::vec3(0.0f));
                }
            }
    }
}

} // namespace
} // namespace cutaway::test
