#include "render/slice_pipeline.hpp"

#include "gpu/check.hpp"
#include "gpu/pipeline.hpp"
#include "slice_frag.spv.h"
#include "slice_id_frag.spv.h"
#include "slice_operator_frag.spv.h"
#include "slice_operator_id_frag.spv.h"
#include "slice_vert.spv.h"

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

gpu::PipelineHandle createSlicePipeline(const gpu::Context& ctx, VkPipelineLayout layout,
                                        SliceProxy proxy, bool withOperatorId) {
    auto vert = gpu::createShaderModule(ctx, slice_vert_spv, sizeof(slice_vert_spv));
    auto frag = fragmentShader(ctx, proxy, withOperatorId);
    VkPipelineShaderStageCreateInfo stages[2] = {
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
         VK_SHADER_STAGE_VERTEX_BIT, vert.get(), "main", nullptr},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
         VK_SHADER_STAGE_FRAGMENT_BIT, frag.get(), "main", nullptr}};

    VkVertexInputBindingDescription binding{0, sizeof(float) * 3, VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attribute{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0};
    VkPipelineVertexInputStateCreateInfo vertexInput{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertexInput.vertexBindingDescriptionCount = 1;
    vertexInput.pVertexBindingDescriptions = &binding;
    vertexInput.vertexAttributeDescriptionCount = 1;
    vertexInput.pVertexAttributeDescriptions = &attribute;

    VkPipelineInputAssemblyStateCreateInfo assembly{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;

    VkPipelineViewportStateCreateInfo viewport{
        VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;

    VkPipelineRasterizationStateCreateInfo raster{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE; // slice winding depends on the view
    raster.lineWidth = 1.0f;

    VkPipelineMultisampleStateCreateInfo multisample{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;

    VkPipelineDepthStencilStateCreateInfo depth{
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    // Meshes drawn before the slices left their depth: the volume behind them
    // is hidden. Slices write no depth (they are translucent).
    depth.depthTestEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
    depth.stencilTestEnable = VK_TRUE;
    VkStencilOpState stencil{};
    stencil.failOp = VK_STENCIL_OP_KEEP;
    stencil.depthFailOp = VK_STENCIL_OP_KEEP;
    stencil.compareMask = 0xff;
    if (proxy == SliceProxy::Operator) {
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
    const VkPipelineColorBlendAttachmentState blends[2] = {blend, blend}; // same rule for the id
    VkPipelineColorBlendStateCreateInfo blendState{
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blendState.attachmentCount = withOperatorId ? 2u : 1u;
    blendState.pAttachments = blends;

    VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                      VK_DYNAMIC_STATE_STENCIL_REFERENCE};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 3;
    dynamic.pDynamicStates = dynamicStates;

    const VkFormat colorFormats[2] = {ctx.formats().color, kOperatorIdFormat};
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = withOperatorId ? 2u : 1u;
    rendering.pColorAttachmentFormats = colorFormats;
    rendering.depthAttachmentFormat = ctx.formats().depthStencil;
    rendering.stencilAttachmentFormat = ctx.formats().depthStencil;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blendState;
    info.pDynamicState = &dynamic;
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VK_CHECK(vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    return gpu::PipelineHandle(ctx.device(), pipeline);
}

} // namespace cutaway::render
