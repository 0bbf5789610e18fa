#include "bake/volume_upload.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace cutaway::bake {
namespace {

uint16_t texel16(double value, ValueWindow window) {
    const double scale = window.hi > window.lo ? 1.0 / (window.hi - window.lo) : 0.0;
    double t = (value - window.lo) * scale;
    if (!(t > 0.0)) t = 0.0; // also maps NaN to 0
    return static_cast<uint16_t>(std::lround(std::min(t, 1.0) * 65535.0));
}

// Calls f(T{}, offset) for the integer types a table by raw value covers.
template <typename F>
bool withTableType(VoxelType type, F&& f) {
    switch (type) {
    case VoxelType::U8:
        f(uint8_t{}, 0);
        return true;
    case VoxelType::I8:
        f(int8_t{}, 128);
        return true;
    case VoxelType::U16:
        f(uint16_t{}, 0);
        return true;
    case VoxelType::I16:
        f(int16_t{}, 32768);
        return true;
    default:
        return false;
    }
}

template <typename T>
T load(const std::byte* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

} // namespace

ValueTexels::ValueTexels(const Volume& volume, ValueWindow window)
    : m_volume(volume), m_window(window) {
    withTableType(volume.type, [&](auto tag, int offset) {
        using T = decltype(tag);
        constexpr std::size_t kValues = std::size_t(1) << (8 * sizeof(T));
        m_offset = offset;
        m_table.resize(kValues);
        for (std::size_t k = 0; k < kValues; ++k)
            m_table[k] = texel16(volume.slope * double(int(k) - offset) + volume.inter, window);
        // Which raw values occur: the R8 test is over those only.
        std::vector<uint8_t> seen(kValues, 0);
        const std::byte* p = volume.data.data();
        for (std::size_t i = 0, n = volume.voxelCount(); i < n; ++i)
            seen[std::size_t(int(load<T>(p + i * sizeof(T))) + offset)] = 1;
        m_r8 = true;
        for (std::size_t k = 0; k < kValues; ++k)
            m_r8 = m_r8 && (!seen[k] || m_table[k] % 257 == 0);
    });
}

uint16_t ValueTexels::r16(std::size_t i) const {
    if (m_table.empty()) return texel16(m_volume.value(i), m_window);
    uint16_t out = 0;
    withTableType(m_volume.type, [&](auto tag, int offset) {
        using T = decltype(tag);
        out = m_table[std::size_t(int(load<T>(m_volume.data.data() + i * sizeof(T))) + offset)];
    });
    return out;
}

void ValueTexels::write(std::size_t first, std::size_t count, std::byte* dst) const {
    const auto store = [&](std::size_t j, uint16_t t) {
        if (m_r8) {
            dst[j] = static_cast<std::byte>(t / 257);
        } else {
            std::memcpy(dst + 2 * j, &t, 2);
        }
    };
    const bool table = withTableType(m_volume.type, [&](auto tag, int offset) {
        using T = decltype(tag);
        const std::byte* p = m_volume.data.data() + first * sizeof(T);
        for (std::size_t j = 0; j < count; ++j)
            store(j, m_table[std::size_t(int(load<T>(p + j * sizeof(T))) + offset)]);
    });
    if (!table) {
        for (std::size_t j = 0; j < count; ++j)
            store(j, texel16(m_volume.value(first + j), m_window));
    }
}

std::vector<uint16_t> normalizeVolume(const Volume& volume, ValueWindow window) {
    const ValueTexels texels(volume, window);
    std::vector<uint16_t> out(volume.voxelCount());
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = texels.r16(i);
    return out;
}

namespace {

// A 3D image of `format` whose texels `write` makes, sampled (and a storage
// image with `storage`), left in its resting layout (Image::layout) for
// fragment and compute shaders.
gpu::Image uploadValueImage(const gpu::Context& ctx, VkFormat format, glm::ivec3 dims,
                            std::size_t texelBytes, const gpu::TexelWriter& write, bool storage) {
    const VkExtent3D extent{static_cast<uint32_t>(dims.x), static_cast<uint32_t>(dims.y),
                            static_cast<uint32_t>(dims.z)};
    gpu::Image image = gpu::createImage(
        ctx, VK_IMAGE_TYPE_3D, format, extent,
        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
            (storage ? VkImageUsageFlags{VK_IMAGE_USAGE_STORAGE_BIT} : VkImageUsageFlags{0}));
    image.layout = storage ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    gpu::uploadImage(ctx, image, texelBytes, write, image.layout,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    return image;
}

} // namespace

gpu::Image uploadVolume(const gpu::Context& ctx, const Volume& volume, ValueWindow window,
                        bool storage) {
    const ValueTexels texels(volume, window);
    return uploadValueImage(
        ctx, texels.format(), volume.dims, texels.texelBytes(),
        [&](std::size_t first, std::size_t count, std::byte* dst) {
            texels.write(first, count, dst);
        },
        storage && ctx.formats().storageValues);
}

gpu::Image uploadVolume(const gpu::Context& ctx, const Volume& volume, ValueWindow window) {
    return uploadVolume(ctx, volume, window, ctx.tuning().storageValues);
}

const gpu::Image& ValueStorageBindings::standIn(int which) {
    gpu::Image& image = m_standIns[which];
    if (image.image) return image;
    const bool storage = m_ctx.formats().storageValues;
    const VkFormat formats[3] = {storage ? VK_FORMAT_R8_UNORM : VK_FORMAT_R8G8B8A8_UNORM,
                                 storage ? VK_FORMAT_R16_UNORM : VK_FORMAT_R8G8B8A8_UNORM,
                                 VK_FORMAT_R8G8B8A8_SNORM};
    const std::size_t bytes[3] = {storage ? 1u : 4u, storage ? 2u : 4u, 4u};
    const uint32_t zero = 0;
    image = gpu::createStorageVolume(m_ctx, formats[which], {1, 1, 1}, &zero, bytes[which],
                                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    return image;
}

std::array<VkImageView, 2> ValueStorageBindings::views(const gpu::Image& values) {
    std::array<VkImageView, 2> views{};
    const int own = fetchOf(values); // 0: neither binding is the values'
    for (int i = 0; i < 2; ++i)
        views[i] = own == i + 1 ? values.view.get() : standIn(i).view.get();
    return views;
}

VkImageView ValueStorageBindings::gradientView(const gpu::Image& gradients) {
    return gradients.layout == VK_IMAGE_LAYOUT_GENERAL ? gradients.view.get()
                                                       : standIn(2).view.get();
}

int ValueStorageBindings::standIns() const {
    int count = 0;
    for (const gpu::Image& image : m_standIns)
        count += image.image ? 1 : 0;
    return count;
}

gpu::Image uploadMask(const gpu::Context& ctx, const std::vector<uint8_t>& mask, glm::ivec3 dims) {
    if (mask.size() != std::size_t(dims.x) * dims.y * dims.z)
        throw RuntimeError("uploadMask: the mask does not match its dimensions");
    return uploadMask(ctx, dims, [&](std::size_t first, std::size_t count, std::byte* dst) {
        for (std::size_t j = 0; j < count; ++j)
            dst[j] = mask[first + j] ? std::byte{255} : std::byte{0};
    });
}

gpu::Image uploadMask(const gpu::Context& ctx, glm::ivec3 dims, const gpu::TexelWriter& write) {
    return uploadValueImage(ctx, VK_FORMAT_R8_UNORM, dims, 1, write, false);
}

} // namespace cutaway::bake
