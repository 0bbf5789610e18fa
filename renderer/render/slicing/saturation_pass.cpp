#include "render/slicing/saturation_pass.hpp"

#include "saturation_frag.spv.h"
#include "saturation_vert.spv.h"
#include "shared/bindings.h"

namespace cutaway::render {

SaturationPass::SaturationPass(const gpu::Context& ctx, VkSampler nearest)
    : m_ctx(ctx), m_nearest(nearest) {
    m_setLayout = gpu::createSetLayout(
        ctx,
        {{CW_BIND_SATURATION_COMPOSITE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
          VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}},
        "saturation");
    m_layout = gpu::createPipelineLayout(ctx, {m_setLayout.get()}, sizeof(float),
                                         VK_SHADER_STAGE_FRAGMENT_BIT);
    auto vert = gpu::createShaderModule(ctx, saturation_vert_spv, sizeof(saturation_vert_spv));
    auto frag = gpu::createShaderModule(ctx, saturation_frag_spv, sizeof(saturation_frag_spv));
    gpu::GraphicsPipelineParts parts;
    parts.vertex = vert.get();
    parts.fragment = frag.get();
    parts.depthStencil.depthTestEnable = VK_TRUE; // ALWAYS: the write is what matters
    parts.depthStencil.depthWriteEnable = VK_TRUE;
    parts.depthStencil.depthCompareOp = VK_COMPARE_OP_ALWAYS;
    m_pipeline = gpu::createGraphicsPipeline(ctx, m_layout.get(), parts);
}

gpu::DescriptorSet SaturationPass::bind(const gpu::Image& color) const {
    gpu::DescriptorSet set = gpu::allocateDescriptorSet(
        m_ctx, m_setLayout.get(), {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}});
    gpu::writeImageDescriptor(m_ctx, set.set, CW_BIND_SATURATION_COMPOSITE,
                              VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, color.view.get(),
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, m_nearest);
    return set;
}

void SaturationPass::record(VkCommandBuffer cmd, VkDescriptorSet set, const gpu::Image& color,
                            const gpu::Image& depthStencil, float opaqueAlpha) const {
    gpu::transition(cmd, color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    const auto tests =
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    const auto depthAccess = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                             VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    gpu::transition(cmd, depthStencil, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, tests, depthAccess, tests,
                    depthAccess);
    VkRenderingAttachmentInfo ds{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    ds.imageView = depthStencil.view.get();
    ds.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    ds.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    ds.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {color.extent.width, color.extent.height}};
    info.layerCount = 1;
    info.pDepthAttachment = &ds;
    info.pStencilAttachment = &ds;
    vkCmdBeginRendering(cmd, &info);
    const VkViewport viewport{0.0f, 0.0f, float(color.extent.width), float(color.extent.height),
                              0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &info.renderArea);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_layout.get(), 0, 1, &set, 0,
                            nullptr);
    vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(float),
                       &opaqueAlpha);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
    gpu::transition(cmd, depthStencil, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, tests, depthAccess, tests,
                    depthAccess);
    gpu::transition(cmd, color, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
}

} // namespace cutaway::render
