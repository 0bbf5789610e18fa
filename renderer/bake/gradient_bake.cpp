#include "bake/gradient_bake.hpp"

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
                              values.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                              m_sampler.get());
    gpu::writeImageDescriptor(m_ctx, set.set, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, out.view.get(),
                              VK_IMAGE_LAYOUT_GENERAL);

    shader::GradientParams params{};
    params.dims = glm::ivec3(values.extent.width, values.extent.height, values.extent.depth);
    params.magnitudeScale = static_cast<float>(2.0 * std::min({spacing.x, spacing.y, spacing.z}));
    params.halfInvSpacing = glm::vec3(0.5 / spacing);

    m_ctx.submitAndWait([&](VkCommandBuffer cmd) {
        gpu::transition(cmd, out, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_pipeline.get());
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_layout.get(), 0, 1, &set.set,
                                0, nullptr);
        vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(params),
                           &params);
        vkCmdDispatch(cmd, (values.extent.width + 7) / 8, (values.extent.height + 7) / 8,
                      (values.extent.depth + 3) / 4);
        gpu::transition(cmd, out, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
    });
    return out;
}

} // namespace cutaway::bake
