#include "bake/volume_upload.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>

namespace cutaway::bake {

std::vector<uint16_t> normalizeVolume(const Volume& volume, ValueWindow window) {
    const std::size_t n = volume.voxelCount();
    std::vector<uint16_t> texels(n);
    const double scale = window.hi > window.lo ? 1.0 / (window.hi - window.lo) : 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        double t = (volume.value(i) - window.lo) * scale;
        if (!(t > 0.0)) t = 0.0; // also maps NaN to 0
        texels[i] = static_cast<uint16_t>(std::lround(std::min(t, 1.0) * 65535.0));
    }
    return texels;
}

gpu::Image uploadVolume(const gpu::Context& ctx, const Volume& volume, ValueWindow window) {
    std::vector<uint16_t> texels = normalizeVolume(volume, window);
    VkExtent3D extent{static_cast<uint32_t>(volume.dims.x), static_cast<uint32_t>(volume.dims.y),
                      static_cast<uint32_t>(volume.dims.z)};
    return gpu::createSampledVolume(
        ctx, VK_FORMAT_R16_UNORM, extent, texels.data(), texels.size() * sizeof(uint16_t),
        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

gpu::Image uploadMask(const gpu::Context& ctx, const std::vector<uint8_t>& mask, glm::ivec3 dims) {
    if (mask.size() != std::size_t(dims.x) * dims.y * dims.z)
        throw RuntimeError("uploadMask: the mask does not match its dimensions");
    std::vector<uint8_t> texels(mask.size());
    std::transform(mask.begin(), mask.end(), texels.begin(),
                   [](uint8_t m) { return m ? uint8_t(255) : uint8_t(0); });
    VkExtent3D extent{static_cast<uint32_t>(dims.x), static_cast<uint32_t>(dims.y),
                      static_cast<uint32_t>(dims.z)};
    return gpu::createSampledVolume(ctx, VK_FORMAT_R8_UNORM, extent, texels.data(), texels.size(),
                                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

} // namespace cutaway::bake
