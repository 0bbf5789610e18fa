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
    gpu::computeIntoImage(m_ctx, out, m_pipeline.get(), m_layout.get(), set.set, &push,
                          sizeof(push), glm::uvec3(8, 8, 4));
    return out;
}

} // namespace cutaway::bake
