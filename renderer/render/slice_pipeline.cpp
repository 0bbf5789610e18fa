#include "render/slice_pipeline.hpp"

#include "gpu/pipeline.hpp"
#include "slice_frag.spv.h"
#include "slice_id_frag.spv.h"
#include "slice_operator_frag.spv.h"
#include "slice_operator_id_frag.spv.h"
#include "slice_vert.spv.h"

#include <cassert>

namespace cutaway::render {

namespace {

gpu::ShaderModuleHandle fragmentShader(const gpu::Context& ctx, SliceProxy proxy,
                                       bool withOperatorId) {
    if (proxy == SliceProxy::Operator)
        return withOperatorId ? gpu::createShaderModule(ctx, slice_operator_id_frag_spv,
                                                        sizeof(slice_operator_id_frag_spv))
                              : gpu::createShaderModule(ctx, slice_operator_frag_spv,
                                                        sizeof(slice_operator_frag_spv));
    return withOperatorId
               ? gpu::createShaderModule(ctx, slice_id_frag_spv, sizeof(slice_id_frag_spv))
               : gpu::createShaderModule(ctx, slice_frag_spv, sizeof(slice_frag_spv));
}

} // namespace

SliceConstants::SliceConstants(const SliceVariant& v, std::initializer_list<uint32_t> more)
    : m_values{v.preintegrated,
               v.byLabel,
               v.shading,
               static_cast<uint32_t>(v.lights),
               static_cast<uint32_t>(v.alignment),
               static_cast<uint32_t>(v.storageFetch)} { // booleans are 32-bit VkBool32
    assert(more.size() <= kMore);
    uint32_t at = kFixed;
    for (uint32_t value : more)
        m_values[at++] = value;
    while (at < kCensus)
        m_values[at++] = 0;
    m_values[kCensus] = v.census;
    m_values[kCensus + 1] = v.brickedGradients;
    m_values[kCensus + 2] = static_cast<uint32_t>(v.wholeShininess);
    for (uint32_t i = 0; i < kMost; ++i)
        m_entries[i] = {i, i * 4u, 4u};
    m_info = {kMost, m_entries, kMost * 4u, m_values};
}

gpu::PipelineHandle createSlicePipeline(const gpu::Context& ctx, VkPipelineLayout layout,
                                        const SliceVariant& variant) {
    const SliceProxy proxy = variant.proxy;
    const bool withOperatorId = variant.withOperatorId;
    const bool stencilOnly = proxy == SliceProxy::OperatorStencil;
    auto vert = gpu::createShaderModule(ctx, slice_vert_spv, sizeof(slice_vert_spv));
    gpu::ShaderModuleHandle frag;
    if (!stencilOnly) frag = fragmentShader(ctx, proxy, withOperatorId);
    const SliceConstants constants(variant);
    gpu::GraphicsPipelineParts parts;
    parts.vertex = vert.get();
    parts.fragment = frag.get();
    // Slice polygons arrive in world space, clipped on the CPU.
    parts.bindings = {{0, sizeof(float) * 3, VK_VERTEX_INPUT_RATE_VERTEX}};
    parts.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}};

    // Meshes drawn before the slices left their depth: the volume behind them
    // is hidden. Slices write no depth (they are translucent).
    VkPipelineDepthStencilStateCreateInfo& depth = parts.depthStencil;
    depth.depthTestEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
    depth.stencilTestEnable = VK_TRUE;
    VkStencilOpState stencil{};
    stencil.failOp = VK_STENCIL_OP_KEEP;
    stencil.depthFailOp = VK_STENCIL_OP_KEEP;
    stencil.compareMask = 0xff;
    if (proxy != SliceProxy::Background) {
        stencil.compareOp = VK_COMPARE_OP_ALWAYS;
        stencil.passOp = VK_STENCIL_OP_REPLACE;
        stencil.writeMask = 0xff;
    } else {
        stencil.compareOp = VK_COMPARE_OP_NOT_EQUAL;
        stencil.passOp = VK_STENCIL_OP_KEEP;
        stencil.writeMask = 0;
    }
    depth.front = stencil;
    depth.back = stencil;

    // Front to back "under": dst.rgb += (1 - dst.a) * src.rgb, same for alpha,
    // with src premultiplied. Primitives blend in submission order.
    VkPipelineColorBlendAttachmentState blend{};
    blend.blendEnable = VK_TRUE;
    blend.srcColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
    blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.colorBlendOp = VK_BLEND_OP_ADD;
    blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
    blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.alphaBlendOp = VK_BLEND_OP_ADD;
    blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                           VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    if (stencilOnly) {
        blend.blendEnable = VK_FALSE;
        blend.colorWriteMask = 0;
    }
    parts.blends = {blend};
    parts.colorFormats = {ctx.formats().color};
    if (withOperatorId) { // same rule for the id target
        parts.blends.push_back(blend);
        parts.colorFormats.push_back(kOperatorIdFormat);
    }
    parts.extraDynamicStates = {VK_DYNAMIC_STATE_STENCIL_REFERENCE};
    parts.fragmentConstants = stencilOnly ? nullptr : constants.info();
    return gpu::createGraphicsPipeline(ctx, layout, parts);
}

} // namespace cutaway::render
