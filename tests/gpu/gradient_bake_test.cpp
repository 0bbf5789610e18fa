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

// The baked texels (4 bytes each) in the grid's order, whichever the layout.
std::vector<int8_t> gridTexels(const gpu::Context& ctx, const gpu::Image& gradients,
                               glm::ivec3 dims, bake::GradientLayout layout) {
    const std::vector<std::byte> bytes = gpu::downloadImage(ctx, gradients, gradients.layout, 4);
    const auto* texels = reinterpret_cast<const int8_t*>(bytes.data());
    const VkExtent3D e = gradients.extent;
    std::vector<int8_t> grid(4 * std::size_t(dims.x) * dims.y * dims.z);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const glm::ivec3 v(x, y, z);
                const glm::ivec3 t =
                    layout == bake::GradientLayout::Bricked ? shader::gradientBrickTexel(v) : v;
                const std::size_t from =
                    std::size_t(t.x) + e.width * (t.y + std::size_t(e.height) * t.z);
                const std::size_t to = std::size_t(x) + dims.x * (y + std::size_t(dims.y) * z);
                std::copy_n(texels + 4 * from, 4, grid.begin() + std::ptrdiff_t(4 * to));
            }
    return grid;
}

constexpr bake::GradientLayout kLayouts[] = {bake::GradientLayout::Linear,
                                             bake::GradientLayout::Bricked};

} // namespace

TEST_F(GpuTest, GradientBakeMatchesCpuReference) {
    const glm::ivec3 dims(13, 11, 9);
    const glm::dvec3 spacing(0.7, 1.3, 2.5); // anisotropic: division by spacing must happen
    Volume volume = randomVolume(dims, spacing, 7);
    const ValueRange range = valueRange(volume);
    const bake::ValueWindow window{range.min, range.max};

    bake::GradientBaker baker(ctx());
    gpu::Image values = bake::uploadVolume(ctx(), volume, window);
    const std::vector<glm::vec4> expected = cpuGradients(volume, window);
    for (const bake::GradientLayout layout : kLayouts) {
        SCOPED_TRACE(layout == bake::GradientLayout::Bricked ? "bricked" : "linear");
        const std::vector<int8_t> texels =
            gridTexels(ctx(), baker.bake(values, spacing, layout), dims, layout);
        float maxErr = 0.0f;
        for (std::size_t i = 0; i < volume.voxelCount(); ++i)
            for (int c = 0; c < 4; ++c) {
                const float got = std::max(texels[4 * i + std::size_t(c)] / 127.0f, -1.0f);
                maxErr = std::max(maxErr, std::abs(got - expected[i][c]));
            }
        // SNORM8 quantization is 1/254 at best; allow one step of rounding difference.
        EXPECT_LE(maxErr, 1.0f / 127.0f + 1e-6f);
    }
}

// Both layouts hold the same texels, to the bit, on a grid whose sides are
// not multiples of the bricks' 4 (the bake's runs and columns cover the grid,
// not the larger bricked image).
TEST_F(GpuTest, BrickedGradientsHoldTheGridsTexels) {
    const glm::ivec3 dims(61, 23, 18);
    const Volume volume = randomVolume(dims, glm::dvec3(1.0, 0.8, 1.5), 5);
    const ValueRange range = valueRange(volume);
    bake::GradientBaker baker(ctx());
    const gpu::Image values = bake::uploadVolume(ctx(), volume, {range.min, range.max});
    const gpu::Image bricked = baker.bake(values, volume.spacing, bake::GradientLayout::Bricked);
    const glm::ivec3 extent = shader::gradientBrickExtent(dims);
    EXPECT_EQ(glm::ivec3(bricked.extent.width, bricked.extent.height, bricked.extent.depth),
              extent);
    const std::vector<int8_t> a =
        gridTexels(ctx(), baker.bake(values, volume.spacing, bake::GradientLayout::Linear), dims,
                   bake::GradientLayout::Linear);
    const std::vector<int8_t> b = gridTexels(ctx(), bricked, dims, bake::GradientLayout::Bricked);
    ASSERT_EQ(a.size(), b.size());
    std::size_t differ = 0, nonZero = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        differ += a[i] != b[i];
        nonZero += a[i] != 0;
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_GT(nonZero, a.size() / 2) << "the gradients must not all vanish";
}

// Reading the values as a storage image (the default on CPU devices) bakes
// the same texels to the bit as sampling them, for R8 and R16 values, in
// both layouts; the grid's sides are not multiples of the runs or columns.
TEST_F(GpuTest, StorageFetchBakesTheSameGradientsAsSampling) {
    if (!ctx().formats().storageValues) GTEST_SKIP() << "the device cannot store R8 and R16 images";
    const glm::ivec3 dims(37, 29, 21);
    const glm::dvec3 spacing(0.9, 1.1, 1.7);
    const Volume wide = randomVolume(dims, spacing, 3);
    Volume narrow = Volume::allocate(dims, VoxelType::U8, spacing); // R8 over [0, 255]
    for (std::size_t i = 0; i < narrow.voxelCount(); ++i)
        narrow.data[i] = std::byte(reinterpret_cast<const uint16_t*>(wide.data.data())[i] >> 8);
    const ValueRange range = valueRange(wide);
    const std::pair<const Volume*, bake::ValueWindow> cases[] = {{&wide, {range.min, range.max}},
                                                                 {&narrow, {0.0, 255.0}}};
    for (const auto& [volume, window] : cases) {
        const gpu::Image values = bake::uploadVolume(ctx(), *volume, window, true);
        SCOPED_TRACE(values.format == VK_FORMAT_R8_UNORM ? "R8" : "R16");
        EXPECT_EQ(values.format, volume == &narrow ? VK_FORMAT_R8_UNORM : VK_FORMAT_R16_UNORM);
        for (const bake::GradientLayout layout : kLayouts) {
            std::vector<int8_t> baked[2];
            for (int storage = 0; storage < 2; ++storage) {
                gpu::DeviceTuning tuning = gpu::kCpuTuning;
                tuning.storageValues = storage == 1;
                const bake::GradientBaker baker(ctx(), tuning);
                ASSERT_EQ(baker.storageFetch(), storage == 1);
                baked[storage] =
                    gridTexels(ctx(), baker.bake(values, spacing, layout), dims, layout);
            }
            std::size_t differ = 0, nonZero = 0;
            for (std::size_t i = 0; i < baked[0].size(); ++i) {
                differ += baked[0][i] != baked[1][i];
                nonZero += baked[0][i] != 0;
            }
            EXPECT_EQ(differ, 0u);
            EXPECT_GT(nonZero, baked[0].size() / 2) << "the gradients must not all vanish";
        }
    }
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
    const bake::GradientLayout layout = bake::gradientLayoutFor(ctx(), ctx().tuning(), dims);
    const auto bakeOf = [&](const Volume& vol) {
        const gpu::Image values = bake::uploadVolume(ctx(), vol, {range.min, range.max});
        return gridTexels(ctx(), baker.bake(values, vol.spacing, layout), dims, layout);
    };
    const std::vector<int8_t> ga = bakeOf(volume), gb = bakeOf(mirrored);
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

// Bricked on CPU devices up to the widest grid whose bricked image (4x as
// wide) fits the device's 3D images, linear beyond it and on GPUs.
TEST_F(GpuTest, GradientsAreBrickedOnCpuDevicesWhereTheyFit) {
    const bool cpu = ctx().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    const int widest = static_cast<int>(ctx().properties().limits.maxImageDimension3D) / 4;
    EXPECT_EQ(bake::gradientLayoutFor(ctx(), ctx().tuning(), {widest, 9, 5}),
              cpu ? bake::GradientLayout::Bricked : bake::GradientLayout::Linear);
    EXPECT_EQ(bake::gradientLayoutFor(ctx(), ctx().tuning(), {widest + 1, 9, 5}),
              bake::GradientLayout::Linear);
}

} // namespace cutaway::test
