#include "bake/operator_bake.hpp"

#include "gpu/pipeline.hpp"
#include "operator_bake_comp.spv.h"
#include "shared/operator_frame.h"

namespace cutaway::bake {

OperatorBaker::OperatorBaker(const gpu::Context& ctx) : m_ctx(ctx) {
    m_setLayout = gpu::createSetLayout(
        ctx, {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}});
    m_layout = gpu::createPipelineLayout(ctx, m_setLayout.get(), sizeof(shader::OperatorBakeParams),
                                         VK_SHADER_STAGE_COMPUTE_BIT);
    auto module =
        gpu::createShaderModule(ctx, operator_bake_comp_spv, sizeof(operator_bake_comp_spv));
    m_pipeline = gpu::createComputePipeline(ctx, m_layout.get(), module.get());
}

gpu::Image OperatorBaker::bake(const shader::OperatorParams& params, glm::vec3 lo, glm::vec3 hi,
                               glm::ivec3 dims) const {
    const VkExtent3D extent{uint32_t(dims.x), uint32_t(dims.y), uint32_t(dims.z)};
    gpu::Image out = gpu::createImage(
        m_ctx, VK_IMAGE_TYPE_3D, VK_FORMAT_R16G16B16A16_SFLOAT, extent,
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    gpu::DescriptorSet set = gpu::allocateDescriptorSet(m_ctx, m_setLayout.get(),
                                                        {{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}});
    gpu::writeImageDescriptor(m_ctx, set.set, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, out.view.get(),
                              VK_IMAGE_LAYOUT_GENERAL);
    shader::OperatorBakeParams push{};
    push.a = params.a;
    push.b = params.b;
    push.kind = params.kind;
    push.mapLo = glm::vec4(lo, 0.0f);
    push.mapHi = glm::vec4(hi, 0.0f);
    push.dims = dims;
    m_ctx.submitAndWait([&](VkCommandBuffer cmd) {
        gpu::transition(cmd, out, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_pipeline.get());
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_layout.get(), 0, 1, &set.set,
                                0, nullptr);
        vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push),
                           &push);
        vkCmdDispatch(cmd, (extent.width + 3) / 4, (extent.height + 3) / 4, (extent.depth + 3) / 4);
        gpu::transition(cmd, out, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
    });
    return out;
}

} // namespace cutaway::bake
