// The gradients' encoding and bricked layout (shaders/shared/gradient.h), on
// the CPU; tests/gpu/gradient_bake_test.cpp checks the bake against them.
#include "shared/gradient.h"

#include <gtest/gtest.h>
#include <vector>

namespace cutaway::test {

// The bricked layout puts each voxel of a grid in a texel of its own inside
// the extent, and each 4x4 patch in x and y in 16 consecutive texels of a row
// (one cache line of RGBA8), the patches of a band of rows one after another.
TEST(GradientBricks, EachVoxelHasItsOwnTexelAndPatchesShareARow) {
    const glm::ivec3 dims(13, 10, 7);
    const glm::ivec3 extent = shader::gradientBrickExtent(dims);
    EXPECT_EQ(extent, glm::ivec3(64, 12, 2));
    std::vector<int> owner(std::size_t(extent.x) * extent.y * extent.z, -1);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const glm::ivec3 t = shader::gradientBrickTexel(glm::ivec3(x, y, z));
                ASSERT_TRUE(glm::all(glm::greaterThanEqual(t, glm::ivec3(0))) &&
                            glm::all(glm::lessThan(t, extent)))
                    << x << " " << y << " " << z;
                int& o = owner[std::size_t(t.x) + extent.x * (t.y + std::size_t(extent.y) * t.z)];
                ASSERT_EQ(o, -1) << "two voxels in one texel at " << x << " " << y << " " << z;
                o = x + dims.x * (y + dims.y * z);
                // The patch's 16 texels: the same row, 16 apart per patch.
                const glm::ivec3 corner = shader::gradientBrickTexel(glm::ivec3(x & ~3, y & ~3, z));
                EXPECT_EQ(t.y, corner.y);
                EXPECT_EQ(t.z, corner.z);
                EXPECT_EQ(corner.x % 16, 0);
                EXPECT_EQ(t.x - corner.x, (x & 3) + 4 * (y & 3));
                EXPECT_EQ(corner.x / 16, x / 4);
            }
}

TEST(GradientEncoding, PointsTowardIncreasingValueAndHonoursSpacing) {
    shader::GradientParams p{};
    p.magnitudeScale = 2.0f;
    p.halfInvSpacing = glm::vec3(0.5f / 1.0f, 0.5f / 1.0f, 0.5f / 4.0f);
    // Same value change per voxel along x and z, but z voxels are 4x longer.
    glm::vec4 g = shader::encodeGradient(glm::vec3(0.2f, 0.0f, 0.2f), p);
    EXPECT_NEAR(glm::length(glm::vec3(g)), 1.0f, 1e-5f);
    EXPECT_NEAR(g.x / g.z, 4.0f, 1e-4f);
    EXPECT_GT(g.x, 0.0f);
    EXPECT_EQ(shader::encodeGradient(glm::vec3(0.0f), p), glm::vec4(0.0f));
}

} // namespace cutaway::test
