#include "render/slicing/slice_pipeline.hpp"

#include "gpu/pipeline.hpp"
#include "slice_frag.spv.h"
#include "slice_id_frag.spv.h"
#include "slice_id_mattes_frag.spv.h"
#include "slice_id_storage_frag.spv.h"
#include "slice_id_storage_mattes_frag.spv.h"
#include "slice_operator_frag.spv.h"
#include "slice_operator_id_frag.spv.h"
#include "slice_operator_id_mattes_frag.spv.h"
#include "slice_operator_id_storage_frag.spv.h"
#include "slice_operator_id_storage_mattes_frag.spv.h"
#include "slice_operator_storage_frag.spv.h"
#include "slice_storage_frag.spv.h"
#include "slice_vert.spv.h"

namespace cutaway::render {

namespace {

using gpu::Spirv;
using gpu::spirv;

// The fragment shader of `proxy`'s polygons for `variant`: each comes plain
// and in the storage flavour (CW_STORAGE_PATHS, shaders/CMakeLists.txt), and
// the one that writes the id target also with the mattes (CW_WRITE_MATTES).
Spirv fragmentSpirv(SliceProxy proxy, const ShaderVariant& variant) {
    const bool storage = variant.storageImages, mattes = variant.mattes;
    if (proxy == SliceProxy::Operator) {
        if (variant.withAovs && mattes)
            return storage ? spirv(slice_operator_id_storage_mattes_frag_spv)
                           : spirv(slice_operator_id_mattes_frag_spv);
        if (variant.withAovs)
            return storage ? spirv(slice_operator_id_storage_frag_spv)
                           : spirv(slice_operator_id_frag_spv);
        return storage ? spirv(slice_operator_storage_frag_spv) : spirv(slice_operator_frag_spv);
    }
    if (variant.withAovs && mattes)
        return storage ? spirv(slice_id_storage_mattes_frag_spv) : spirv(slice_id_mattes_frag_spv);
    if (variant.withAovs)
        return storage ? spirv(slice_id_storage_frag_spv) : spirv(slice_id_frag_spv);
    return storage ? spirv(slice_storage_frag_spv) : spirv(slice_frag_spv);
}

} // namespace

gpu::PipelineHandle createSlicePipeline(const gpu::Context& ctx, VkPipelineLayout layout,
                                        const ShaderVariant& variant, SliceProxy proxy) {
    const bool stencilOnly = proxy == SliceProxy::OperatorStencil;
    auto vert = gpu::createShaderModule(ctx, slice_vert_spv, sizeof(slice_vert_spv));
    gpu::ShaderModuleHandle frag;
    if (!stencilOnly) frag = gpu::createShaderModule(ctx, fragmentSpirv(proxy, variant));
    const ShaderConstants constants(variant);
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
    // The same rule for the id and matte targets, of the colour's format.
    for (std::size_t i = 1; i < aovTargetCount(variant); ++i) {
        parts.blends.push_back(blend);
        parts.colorFormats.push_back(ctx.formats().color);
    }
    parts.extraDynamicStates = {VK_DYNAMIC_STATE_STENCIL_REFERENCE};
    parts.fragmentConstants = stencilOnly ? nullptr : constants.info();
    return gpu::createGraphicsPipeline(ctx, layout, parts);
}

} // namespace cutaway::render
