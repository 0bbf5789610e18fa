#include "bake/operator_bake.hpp"

#include "gpu/pipeline.hpp"
#include "operator_bake_comp.spv.h"
#include "operator_derivative_comp.spv.h"
#include "shared/operator_frame.h"

namespace cutaway::bake {

namespace {

constexpr VkFormat kMapFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr glm::uvec3 kGroup(8, 8, 4); // both shaders' local size

} // namespace

OperatorBaker::OperatorBaker(const gpu::Context& ctx) : m_ctx(ctx) {
    const auto compute = VK_SHADER_STAGE_COMPUTE_BIT;
    m_setLayout = gpu::createSetLayout(
        ctx, {{CW_OPBAKE_BIND_MAP, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, compute, nullptr}},
        "operator bake");
    m_layout = gpu::createPipelineLayout(ctx, m_setLayout.get(), sizeof(shader::OperatorBakeParams),
                                         compute);
    auto module =
        gpu::createShaderModule(ctx, operator_bake_comp_spv, sizeof(operator_bake_comp_spv));
    m_pipeline = gpu::createComputePipeline(ctx, m_layout.get(), module.get());

    m_derivativeSetLayout = gpu::createSetLayout(
        ctx,
        {{CW_OPBAKE_BIND_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, compute, nullptr},
         {CW_OPBAKE_BIND_DERIVATIVES, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, compute, nullptr}},
        "operator derivatives");
    m_derivativeLayout = gpu::createPipelineLayout(ctx, m_derivativeSetLayout.get(),
                                                   sizeof(shader::OperatorBakeParams), compute);
    auto derivative = gpu::createShaderModule(ctx, operator_derivative_comp_spv,
                                              sizeof(operator_derivative_comp_spv));
    m_derivativePipeline =
        gpu::createComputePipeline(ctx, m_derivativeLayout.get(), derivative.get());
    m_nearest = gpu::createNearestSampler(ctx); // texelFetch: any sampler will do
}

BakedMap OperatorBaker::bake(const shader::OperatorParams& params, glm::vec3 lo, glm::vec3 hi,
                             glm::ivec3 dims) const {
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    BakedMap out;
    out.map = gpu::createImage(m_ctx, VK_IMAGE_TYPE_3D, kMapFormat,
                               {uint32_t(dims.x), uint32_t(dims.y), uint32_t(dims.z)}, usage);
    const glm::ivec3 half = derivativeDims(dims);
    out.derivatives =
        gpu::createImage(m_ctx, VK_IMAGE_TYPE_3D, kMapFormat,
                         {uint32_t(3 * half.x), uint32_t(half.y), uint32_t(half.z)}, usage);
    gpu::DescriptorSet set = gpu::allocateDescriptorSet(m_ctx, m_setLayout.get(),
                                                        {{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}});
    gpu::writeImageDescriptor(m_ctx, set.set, CW_OPBAKE_BIND_MAP, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                              out.map.view.get(), VK_IMAGE_LAYOUT_GENERAL);
    gpu::DescriptorSet derivativeSet = gpu::allocateDescriptorSet(
        m_ctx, m_derivativeSetLayout.get(),
        {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}});
    gpu::writeImageDescriptor(m_ctx, derivativeSet.set, CW_OPBAKE_BIND_MAP,
                              VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, out.map.view.get(),
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, m_nearest.get());
    gpu::writeImageDescriptor(m_ctx, derivativeSet.set, CW_OPBAKE_BIND_DERIVATIVES,
                              VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, out.derivatives.view.get(),
                              VK_IMAGE_LAYOUT_GENERAL);
    shader::OperatorBakeParams push{};
    push.a = params.a;
    push.b = params.b;
    push.kind = params.kind;
    push.mapLo = glm::vec4(lo, 0.0f);
    push.mapHi = glm::vec4(hi, 0.0f);
    push.dims = dims;
    gpu::computeIntoImage(m_ctx, out.map, m_pipeline.get(), m_layout.get(), set.set, &push,
                          sizeof(push), kGroup);
    // The derivatives read the map's texels the first pass wrote.
    gpu::computeIntoImage(m_ctx, out.derivatives, m_derivativePipeline.get(),
                          m_derivativeLayout.get(), derivativeSet.set, &push, sizeof(push), kGroup);
    out.map.layout = out.derivatives.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    return out;
}

} // namespace cutaway::bake
