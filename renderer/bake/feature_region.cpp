#include "bake/feature_region.hpp"

#include "bake/feature_bake.hpp"
#include "bake/volume_upload.hpp"
#include "feature_region_comp.spv.h"
#include "gpu/pipeline.hpp"
#include "shared/feature_bake.h"

#include <cmath>

namespace cutaway::bake {

VoxelRegion regionCovering(glm::ivec3 dims, glm::dvec3 spacing, glm::dvec3 gridLo, glm::dvec3 boxLo,
                           glm::dvec3 boxHi, int margin) {
    // Voxel centres sit at whole voxel coordinates.
    const glm::dvec3 lo = glm::floor((boxLo - gridLo) / spacing - 0.5) - double(margin);
    const glm::dvec3 hi = glm::ceil((boxHi - gridLo) / spacing - 0.5) + double(margin);
    const glm::dvec3 top(dims - 1);
    const glm::ivec3 first(glm::clamp(lo, glm::dvec3(0.0), top));
    const glm::ivec3 last(glm::clamp(hi, glm::dvec3(first), top));
    return {first, last - first + 1};
}

FeatureRegionBaker::FeatureRegionBaker(const gpu::Context& ctx) : m_ctx(ctx) {
    const auto cs = VK_SHADER_STAGE_COMPUTE_BIT;
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    m_setLayout = gpu::createSetLayout(
        ctx,
        {{CW_REGION_BIND_VALUES, sampled, 1, cs, nullptr},
         {CW_REGION_BIND_MASK, sampled, 1, cs, nullptr},
         {CW_REGION_BIND_OUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr}},
        "feature region");
    m_layout =
        gpu::createPipelineLayout(ctx, m_setLayout.get(), sizeof(shader::FeatureRegionParams), cs);
    auto module =
        gpu::createShaderModule(ctx, feature_region_comp_spv, sizeof(feature_region_comp_spv));
    m_pipeline = gpu::createComputePipeline(ctx, m_layout.get(), module.get());
    m_sampler = gpu::createNearestSampler(ctx);
}

gpu::Image FeatureRegionBaker::bake(const gpu::Image& values, const gpu::Image& mask,
                                    VoxelRegion region) const {
    const glm::uvec3 n(region.size);
    gpu::Image out = gpu::createImage(
        m_ctx, VK_IMAGE_TYPE_3D, VK_FORMAT_R16G16_SFLOAT, {n.x, n.y, n.z},
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    gpu::DescriptorSet set = gpu::allocateDescriptorSet(
        m_ctx, m_setLayout.get(),
        {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}});
    gpu::writeImageDescriptor(m_ctx, set.set, CW_REGION_BIND_VALUES,
                              VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, values.view.get(),
                              values.layout, m_sampler.get());
    gpu::writeImageDescriptor(m_ctx, set.set, CW_REGION_BIND_MASK,
                              VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, mask.view.get(),
                              kFeatureLayout, m_sampler.get());
    gpu::writeImageDescriptor(m_ctx, set.set, CW_REGION_BIND_OUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                              out.view.get(), VK_IMAGE_LAYOUT_GENERAL);
    shader::FeatureRegionParams params{};
    params.lo = region.lo;
    params.size = region.size;
    params.dims = glm::ivec3(values.extent.width, values.extent.height, values.extent.depth);
    gpu::computeIntoImage(m_ctx, out, m_pipeline.get(), m_layout.get(), set.set, &params,
                          sizeof params, glm::uvec3(8, 8, 4)); // one workgroup each
    out.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    return out;
}

} // namespace cutaway::bake
