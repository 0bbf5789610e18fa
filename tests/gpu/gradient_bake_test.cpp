// The GPU gradient bake against the CPU evaluation of the same shared header.
#include "bake/gradient_bake.hpp"
#include "bake/volume_upload.hpp"
#include "cpu_reference.hpp"
#include "gpu_fixture.hpp"
#include "shared/gradient.h"

#include <gtest/gtest.h>
#include <random>

namespace cutaway::test {
namespace {

Volume randomVolume(glm::ivec3 dims, glm::dvec3 spacing, unsigned seed) {
    Volume v = Volume::allocate(dims, VoxelType::U16, spacing);
    std::mt19937 rng(seed);
    auto* p = reinterpret_cast<uint16_t*>(v.data.data());
    // Smooth structure plus noise, so gradients have every direction and size.
    std::uniform_int_distribution<int> noise(0, 400);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                p[v.index(x, y, z)] =
                    static_cast<uint16_t>(1000 * x + 700 * y * y / dims.y + 300 * z + noise(rng));
    return v;
}

} // namespace

TEST_F(GpuTest, GradientBakeMatchesCpuReference) {
    const glm::ivec3 dims(13, 11, 9);
    const glm::dvec3 spacing(0.7, 1.3, 2.5); // anisotropic: division by spacing must happen
    Volume volume = randomVolume(dims, spacing, 7);
    const ValueRange range = valueRange(volume);
    const bake::ValueWindow window{range.min, range.max};

    bake::GradientBaker baker(ctx());
    gpu::Image values = bake::uploadVolume(ctx(), volume, window);
    gpu::Image gradients = baker.bake(values, spacing);
    std::vector<std::byte> bytes =
        gpu::downloadImage(ctx(), gradients, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 4);
    const auto* texels = reinterpret_cast<const int8_t*>(bytes.data());

    const std::vector<glm::vec4> expected = cpuGradients(volume, window);
    float maxErr = 0.0f;
    for (std::size_t i = 0; i < volume.voxelCount(); ++i)
        for (int c = 0; c < 4; ++c) {
            const float got = std::max(texels[4 * i + std::size_t(c)] / 127.0f, -1.0f);
            maxErr = std::max(maxErr, std::abs(got - expected[i][c]));
        }
    // SNORM8 quantization is 1/254 at best; allow one step of rounding difference.
    EXPECT_LE(maxErr, 1.0f / 127.0f + 1e-6f);
}

// Mirroring the volume in x mirrors its baked gradient to the bit: x
// negated, the rest equal. The bake adds each voxel's two neighbours before
// anything else, so rounding does not depend on the side, and a symmetric
// scene renders symmetric (render_properties_test).
TEST_F(GpuTest, MirroredVolumeBakesTheMirroredGradientExactly) {
    const glm::ivec3 dims(61, 40, 24); // x not a multiple of the bake's runs
    const Volume volume = randomVolume(dims, glm::dvec3(1.0, 0.8, 1.5), 11);
    Volume mirrored = volume;
    auto* m = reinterpret_cast<uint16_t*>(mirrored.data.data());
    const auto* v = reinterpret_cast<const uint16_t*>(volume.data.data());
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                m[volume.index(x, y, z)] = v[volume.index(dims.x - 1 - x, y, z)];
    const ValueRange range = valueRange(volume);
    bake::GradientBaker baker(ctx());
    const auto bakeOf = [&](const Volume& vol) {
        const gpu::Image values = bake::uploadVolume(ctx(), vol, {range.min, range.max});
        return gpu::downloadImage(ctx(), baker.bake(values, vol.spacing),
                                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 4);
    };
    const std::vector<std::byte> a = bakeOf(volume), b = bakeOf(mirrored);
    const auto* ga = reinterpret_cast<const int8_t*>(a.data());
    const auto* gb = reinterpret_cast<const int8_t*>(b.data());
    int nonZero = 0;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const std::size_t i = 4 * volume.index(x, y, z);
                const std::size_t j = 4 * volume.index(dims.x - 1 - x, y, z);
                nonZero += ga[i] != 0;
                ASSERT_EQ(int(gb[j]), -int(ga[i])) << x << " " << y << " " << z;
                for (int c = 1; c < 4; ++c)
                    ASSERT_EQ(gb[j + c], ga[i + c]) << x << " " << y << " " << z << " c " << c;
            }
    EXPECT_GT(nonZero, dims.x * dims.y * dims.z / 2) << "x gradients must not all vanish";
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
