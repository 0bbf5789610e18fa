#include "bake/gradient_bake.hpp"

#include "bake/volume_upload.hpp"
#include "gpu/pipeline.hpp"
#include "gradient_comp.spv.h"
#include "shared/gradient.h"

#include <algorithm>

namespace cutaway::bake {

GradientBaker::GradientBaker(const gpu::Context& ctx) : m_ctx(ctx) {
    m_setLayout = gpu::createSetLayout(
        ctx,
        {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
         {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}});
    m_layout = gpu::createPipelineLayout(ctx, m_setLayout.get(), sizeof(shader::GradientParams),
                                         VK_SHADER_STAGE_COMPUTE_BIT);
    auto module = gpu::createShaderModule(ctx, gradient_comp_spv, sizeof(gradient_comp_spv));
    m_pipeline = gpu::createComputePipeline(ctx, m_layout.get(), module.get());
    m_sampler = gpu::createLinearSampler(ctx);
}

gpu::Image GradientBaker::bake(const gpu::Image& values, glm::dvec3 spacing) const {
    gpu::Image out = gpu::createImage(
        m_ctx, VK_IMAGE_TYPE_3D, VK_FORMAT_R8G8B8A8_SNORM, values.extent,
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    gpu::DescriptorSet set = gpu::allocateDescriptorSet(
        m_ctx, m_setLayout.get(),
        {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}});
    gpu::writeImageDescriptor(m_ctx, set.set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                              values.view.get(), kValuesLayout, m_sampler.get());
    gpu::writeImageDescriptor(m_ctx, set.set, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, out.view.get(),
                              VK_IMAGE_LAYOUT_GENERAL);

    shader::GradientParams params{};
    params.dims = glm::ivec3(values.extent.width, values.extent.height, values.extent.depth);
    params.magnitudeScale = static_cast<float>(2.0 * std::min({spacing.x, spacing.y, spacing.z}));
    params.halfInvSpacing = glm::vec3(0.5 / spacing);

    gpu::computeIntoImage(m_ctx, out, m_pipeline.get(), m_layout.get(), set.set, &params,
                          sizeof(params), glm::uvec3(8 * 4, 8, 16)); // kRun wide, kColumn deep
    return out;
}

} // namespace cutaway::bake
