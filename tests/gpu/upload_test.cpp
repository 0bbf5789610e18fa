// Uploads: texels streamed through a bounded staging buffer land where they
// belong across chunk boundaries, and the value texture is R8 exactly when
// R8 holds the numbers R16 would.
#include "bake/volume_upload.hpp"
#include "gpu_fixture.hpp"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <random>

namespace cutaway::test {
namespace {

// A texel's bytes from its index: every byte differs from its neighbours', so
// a chunk copied to the wrong slice or offset cannot go unnoticed.
std::byte patternByte(std::size_t i, std::size_t b) {
    return static_cast<std::byte>((i * 2654435761u >> 13) + 77 * b);
}

// The R16 texel of a value, as the upload has always computed it (by the
// window's reciprocal: a tie such as 19 / 190 * 65535 rounds by its last bit).
uint16_t reference16(double value, bake::ValueWindow w) {
    double t = (value - w.lo) * (1.0 / (w.hi - w.lo));
    if (!(t > 0.0)) t = 0.0;
    return static_cast<uint16_t>(std::lround(std::min(t, 1.0) * 65535.0));
}

template <typename T>
Volume randomVolume(glm::ivec3 dims, VoxelType type, int lo, int hi, unsigned seed) {
    Volume v = Volume::allocate(dims, type);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> value(lo, hi);
    for (std::size_t i = 0; i < v.voxelCount(); ++i) {
        const T t = static_cast<T>(value(rng));
        std::memcpy(v.data.data() + i * sizeof(T), &t, sizeof t);
    }
    return v;
}

} // namespace

TEST_F(GpuTest, StreamedUploadsCrossStagingChunks) {
    // 3D images of one and two bytes per texel, and a 2D array, each larger
    // than the staging buffer and not a multiple of its slices.
    struct Case {
        VkFormat format;
        std::size_t texelBytes;
        VkExtent3D extent;
        uint32_t layers;
    };
    const Case cases[] = {
        {VK_FORMAT_R8_UNORM, 1, {256, 256, 300}, 1},
        {VK_FORMAT_R16_UNORM, 2, {128, 160, 451}, 1},
        {VK_FORMAT_R8_UNORM, 1, {1024, 1024, 1}, 19},
    };
    for (const Case& c : cases) {
        const std::size_t texels =
            std::size_t(c.extent.width) * c.extent.height * c.extent.depth * c.layers;
        ASSERT_GT(texels * c.texelBytes, gpu::kStagingBytes);
        const gpu::Image image =
            c.layers > 1
                ? gpu::createImageArray(
                      ctx(), c.format, {c.extent.width, c.extent.height}, c.layers,
                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                          VK_IMAGE_USAGE_TRANSFER_SRC_BIT)
                : gpu::createImage(ctx(), VK_IMAGE_TYPE_3D, c.format, c.extent,
                                   VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                       VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        std::size_t written = 0;
        gpu::uploadImage(
            ctx(), image, c.texelBytes,
            [&](std::size_t first, std::size_t count, std::byte* dst) {
                EXPECT_EQ(first, written) << "chunks in order, none skipped";
                for (std::size_t j = 0; j < count; ++j)
                    for (std::size_t b = 0; b < c.texelBytes; ++b)
                        dst[j * c.texelBytes + b] = patternByte(first + j, b);
                written += count;
            },
            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
        EXPECT_EQ(written, texels);
        const std::vector<std::byte> back = gpu::downloadImage(
            ctx(), image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, c.texelBytes);
        ASSERT_EQ(back.size(), texels * c.texelBytes);
        std::size_t wrong = 0;
        for (std::size_t i = 0; i < texels; ++i)
            for (std::size_t b = 0; b < c.texelBytes; ++b)
                wrong += back[i * c.texelBytes + b] != patternByte(i, b);
        EXPECT_EQ(wrong, 0u) << c.extent.width << "x" << c.extent.height << "x" << c.extent.depth
                             << " layers " << c.layers;
    }
}

TEST(ValueTexels, R16TexelsFollowTheWindowForEveryType) {
    const glm::ivec3 dims(17, 9, 5);
    struct Case {
        Volume volume;
        bake::ValueWindow window;
    };
    Volume scaled = randomVolume<int16_t>(dims, VoxelType::I16, -3000, 3000, 4);
    scaled.slope = 0.5;
    scaled.inter = -12.0;
    Case cases[] = {
        {randomVolume<uint8_t>(dims, VoxelType::U8, 0, 255, 1), {10.0, 200.0}},
        {randomVolume<int8_t>(dims, VoxelType::I8, -128, 127, 2), {-50.0, 60.0}},
        {randomVolume<uint16_t>(dims, VoxelType::U16, 0, 65535, 3), {0.0, 4095.0}},
        {std::move(scaled), {-1000.0, 1000.0}},
        {randomVolume<int32_t>(dims, VoxelType::I32, -100000, 100000, 5), {-5.0e4, 7.0e4}},
    };
    for (const Case& c : cases) {
        const std::vector<uint16_t> texels = bake::normalizeVolume(c.volume, c.window);
        for (std::size_t i = 0; i < texels.size(); ++i)
            ASSERT_EQ(texels[i], reference16(c.volume.value(i), c.window))
                << voxelTypeName(c.volume.type) << " voxel " << i;
    }
}

TEST_F(GpuTest, ValueTextureIsR8ExactlyWhenR8HoldsTheSameNumbers) {
    const glm::ivec3 dims(19, 13, 7);
    struct Case {
        const char* what;
        Volume volume;
        bake::ValueWindow window;
        VkFormat expected;
    };
    Volume labels = randomVolume<uint16_t>(dims, VoxelType::U16, 0, 20, 7);
    Volume offset = randomVolume<uint8_t>(dims, VoxelType::U8, 0, 255, 8);
    offset.inter = 1.0; // 1..256 over [0, 255]: 0 never occurs, 256 clamps to 255
    Case cases[] = {
        {"uint8 over [0, 255]",
         randomVolume<uint8_t>(dims, VoxelType::U8, 0, 255, 6),
         {0.0, 255.0},
         VK_FORMAT_R8_UNORM},
        {"labels over [0, 1]", std::move(labels), {0.0, 1.0}, VK_FORMAT_R8_UNORM},
        {"uint8 shifted by the intercept", std::move(offset), {0.0, 255.0}, VK_FORMAT_R8_UNORM},
        {"uint8 over [0, 200]",
         randomVolume<uint8_t>(dims, VoxelType::U8, 0, 255, 9),
         {0.0, 200.0},
         VK_FORMAT_R16_UNORM},
        {"uint16 over its range",
         randomVolume<uint16_t>(dims, VoxelType::U16, 0, 4000, 10),
         {0.0, 4000.0},
         VK_FORMAT_R16_UNORM},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        EXPECT_EQ(bake::uploadVolume(ctx(), c.volume, c.window).format, c.expected);
        // The same texels into an image the test can read back.
        const bake::ValueTexels values(c.volume, c.window);
        const VkExtent3D extent{uint32_t(dims.x), uint32_t(dims.y), uint32_t(dims.z)};
        const gpu::Image image =
            gpu::createImage(ctx(), VK_IMAGE_TYPE_3D, values.format(), extent,
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                 VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        gpu::uploadImage(
            ctx(), image, values.texelBytes(),
            [&](std::size_t first, std::size_t count, std::byte* dst) {
                values.write(first, count, dst);
            },
            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
        const std::size_t bytes = values.texelBytes();
        const std::vector<std::byte> back =
            gpu::downloadImage(ctx(), image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, bytes);
        const std::vector<uint16_t> texels = bake::normalizeVolume(c.volume, c.window);
        for (std::size_t i = 0; i < texels.size(); ++i) {
            // The number a shader reads: k / 255 or k / 65535.
            const double got =
                bytes == 1 ? double(uint8_t(back[i])) / 255.0
                           : double(uint8_t(back[2 * i]) | uint8_t(back[2 * i + 1]) << 8) / 65535.0;
            ASSERT_EQ(got, double(texels[i]) / 65535.0) << "voxel " << i;
        }
    }
}

} // namespace cutaway::test
