// The feature fields' ranges over the ray caster's cells
// (bake/feature_ranges.hpp): the compute shader against its CPU twin, and the
// property empty-space skipping relies on: every trilinear sample of the
// field anywhere in a cell lies within the cell's range.
#include "bake/feature_bake.hpp"
#include "bake/feature_ranges.hpp"
#include "bake/volume_upload.hpp"
#include "gpu_fixture.hpp"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <random>

namespace cutaway::test {
namespace {

std::size_t indexOf(glm::ivec3 d, glm::ivec3 v) {
    return std::size_t(v.x) + std::size_t(d.x) * (std::size_t(v.y) + std::size_t(d.y) * v.z);
}

// The field sampled at voxel coordinate `at` (texel centres at whole numbers)
// as the sampler filters it: trilinear, clamped to the edge.
float trilinear(const std::vector<float>& field, glm::ivec3 dims, glm::dvec3 at) {
    const glm::dvec3 pos = glm::clamp(at, glm::dvec3(0.0), glm::dvec3(dims - 1));
    const glm::ivec3 lo(pos);
    const glm::ivec3 hi = glm::min(lo + 1, dims - 1);
    const glm::dvec3 f = pos - glm::dvec3(lo);
    double sum = 0.0;
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 v((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
        const double w =
            ((c & 1) ? f.x : 1.0 - f.x) * ((c & 2) ? f.y : 1.0 - f.y) * ((c & 4) ? f.z : 1.0 - f.z);
        sum += w * double(field[indexOf(dims, v)]);
    }
    return float(sum);
}

class FieldRanges : public GpuTest {};

TEST(FieldRangesCpu, HoldEverySampleInTheirCell) {
    // Odd sizes: partial cells at the far faces; values of both signs.
    const glm::ivec3 dims(13, 10, 7);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> value(-20.0f, 40.0f);
    std::vector<float> field(std::size_t(dims.x) * dims.y * dims.z);
    for (float& v : field)
        v = value(rng);
    for (int cellVoxels : {1, 2, 4}) {
        SCOPED_TRACE(cellVoxels);
        const bake::FieldRanges r = bake::fieldRangesCpu(field, dims, cellVoxels, 2.0f);
        ASSERT_EQ(r.cells, (dims + cellVoxels - 1) / cellVoxels);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        int tight = 0;
        for (int n = 0; n < 20000; ++n) {
            // A point of the grid's box (voxel i spans [i, i + 1) there, its
            // centre at i + 0.5): its cell, and its sample.
            const glm::dvec3 p = glm::dvec3(u(rng), u(rng), u(rng)) * glm::dvec3(dims);
            const glm::ivec3 cell = glm::min(glm::ivec3(p) / cellVoxels, r.cells - 1);
            const float v = trilinear(field, dims, p - 0.5);
            const std::size_t i = indexOf(r.cells, cell);
            ASSERT_LE(r.lohi[2 * i] / 2.0f, v) << p.x << " " << p.y << " " << p.z;
            ASSERT_GE(r.lohi[2 * i + 1] / 2.0f, v) << p.x << " " << p.y << " " << p.z;
            EXPECT_TRUE(r.mayReach(i, double(v)));
            EXPECT_TRUE(r.mayBeBelow(i, double(v) + 1e-3));
            tight += r.lohi[2 * i + 1] - r.lohi[2 * i] <= 2 * 60 + 2;
        }
        EXPECT_EQ(tight, 20000); // no wider than the values' span, rounded out
    }
    // Clamped to a byte: a threshold the steps cannot tell apart is refused.
    const bake::FieldRanges r = bake::fieldRangesCpu(field, dims, 2, 2.0f);
    EXPECT_TRUE(r.resolves(6.0));
    EXPECT_FALSE(r.resolves(63.0));
    EXPECT_FALSE(r.resolves(-64.0));
}

TEST_F(FieldRanges, MatchTheirCpuTwin) {
    // A ball's distance field on an odd, anisotropic grid (a swapped axis or
    // a cell pair's second half would show), and a field without background.
    const glm::ivec3 dims(23, 17, 9);
    const glm::dvec3 spacing(0.8, 1.1, 1.7);
    std::vector<uint8_t> object(std::size_t(dims.x) * dims.y * dims.z);
    const glm::dvec3 centre = glm::dvec3(dims - 1) * 0.5 * spacing;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                object[indexOf(dims, {x, y, z})] =
                    glm::length(glm::dvec3(x, y, z) * spacing - centre) <= 7.5 ? 1 : 0;
    Volume v = Volume::allocate(dims, VoxelType::U8, spacing);
    for (std::size_t i = 0; i < object.size(); ++i)
        v.data[i] = std::byte(object[i] ? 255 : 0);
    bake::FeatureBaker baker(ctx());
    const gpu::Image field =
        baker.distanceField(bake::uploadVolume(ctx(), v, {0.0, 255.0}), spacing, 0.5f);
    const std::vector<float> texels = downloadFeatureField(ctx(), field);
    const bake::FieldRangeBaker ranges(ctx());
    for (int cellVoxels : {1, 2, 3}) {
        SCOPED_TRACE(cellVoxels);
        const bake::FieldRanges gpu = ranges.ranges(field, cellVoxels, 2.0f);
        const bake::FieldRanges cpu = bake::fieldRangesCpu(texels, dims, cellVoxels, 2.0f);
        ASSERT_EQ(gpu.cells, cpu.cells);
        ASSERT_EQ(gpu.lohi.size(), cpu.lohi.size());
        int differ = 0;
        for (std::size_t i = 0; i < cpu.lohi.size(); ++i)
            differ += gpu.lohi[i] != cpu.lohi[i];
        EXPECT_EQ(differ, 0);
        // Not all alike: the ball's inside reaches its depth, its outside 0.
        const auto [least, most] = std::minmax_element(cpu.lohi.begin(), cpu.lohi.end());
        EXPECT_EQ(*least, 0);
        EXPECT_GE(*most, 2 * 5);
    }
}

} // namespace
} // namespace cutaway::test
