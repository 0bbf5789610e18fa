#include "render/raycaster.hpp"

#include "raycast_comp.spv.h"

namespace cutaway::render {
namespace {

struct RayPush { // matches the push constants of shaders/raycast.comp.glsl
    glm::mat4 clipToWorld;
    glm::vec4 boxLo;
    glm::vec4 boxHi;
    glm::vec4 bricksPerTexture;
};

} // namespace

Raycaster::Raycaster(const gpu::Context& ctx, VkSampler linear, VkSampler nearest)
    : m_ctx(ctx), m_linear(linear), m_nearest(nearest) {
    const auto cs = VK_SHADER_STAGE_COMPUTE_BIT;
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    m_setLayout = gpu::createSetLayout(ctx, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, cs, nullptr},
                                             {1, sampled, 1, cs, nullptr},
                                             {2, sampled, 1, cs, nullptr},
                                             {3, sampled, 1, cs, nullptr},
                                             {4, sampled, 1, cs, nullptr},
                                             {5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr},
                                             {6, sampled, 1, cs, nullptr}});
    m_layout = gpu::createPipelineLayout(ctx, m_setLayout.get(), sizeof(RayPush), cs);
}

gpu::DescriptorSet Raycaster::bind(const Inputs& in, const gpu::Image& target) const {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    const auto ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    gpu::DescriptorSet set = gpu::allocateDescriptorSet(m_ctx, m_setLayout.get(),
                                                        {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                                         {sampled, 5},
                                                         {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}});
    gpu::writeBufferDescriptor(m_ctx, set.set, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, in.uniforms,
                               in.uniformBytes);
    gpu::writeImageDescriptor(m_ctx, set.set, 1, sampled, in.values, ro, m_linear);
    gpu::writeImageDescriptor(m_ctx, set.set, 2, sampled, in.gradients, ro, m_linear);
    gpu::writeImageDescriptor(m_ctx, set.set, 3, sampled, in.transfer, ro, m_linear);
    gpu::writeImageDescriptor(m_ctx, set.set, 4, sampled, in.classes, ro, m_nearest);
    gpu::writeImageDescriptor(m_ctx, set.set, 5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                              target.view.get(), VK_IMAGE_LAYOUT_GENERAL);
    gpu::writeImageDescriptor(m_ctx, set.set, 6, sampled, in.bricks, ro, m_nearest);
    return set;
}

VkPipeline Raycaster::pipelineFor(const SliceVariant& variant) {
    auto found = m_pipelines.find(variant);
    if (found == m_pipelines.end()) {
        auto module = gpu::createShaderModule(m_ctx, raycast_comp_spv, sizeof(raycast_comp_spv));
        const SliceConstants constants(variant);
        found = m_pipelines
                    .emplace(variant, gpu::createComputePipeline(m_ctx, m_layout.get(),
                                                                 module.get(), constants.info()))
                    .first;
    }
    return found->second.get();
}

void Raycaster::record(VkCommandBuffer cmd, VkDescriptorSet set, const gpu::Image& target,
                       const CameraMatrices& camera, const Box& occupied,
                       glm::vec3 bricksPerTexture, const SliceVariant& variant) {
    gpu::transition(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                    VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    const RayPush push{glm::mat4(glm::inverse(camera.viewProj)),
                       glm::vec4(glm::vec3(occupied.lo), 0.0f),
                       glm::vec4(glm::vec3(occupied.hi), 0.0f), glm::vec4(bricksPerTexture, 0.0f)};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineFor(variant));
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_layout.get(), 0, 1, &set, 0,
                            nullptr);
    vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, (target.extent.width + 7) / 8, (target.extent.height + 7) / 8, 1);
    gpu::transition(cmd, target, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
}

} // namespace cutaway::render
