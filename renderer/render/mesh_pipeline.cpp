#include "render/mesh_pipeline.hpp"

#include "gpu/pipeline.hpp"
#include "mesh_frag.spv.h"
#include "mesh_vert.spv.h"

#include <cstddef>

namespace cutaway::render {

gpu::PipelineHandle createMeshPipeline(const gpu::Context& ctx, VkPipelineLayout layout) {
    auto vert = gpu::createShaderModule(ctx, mesh_vert_spv, sizeof(mesh_vert_spv));
    auto frag = gpu::createShaderModule(ctx, mesh_frag_spv, sizeof(mesh_frag_spv));
    gpu::GraphicsPipelineParts parts;
    parts.vertex = vert.get();
    parts.fragment = frag.get();
    parts.bindings = {{0, sizeof(MeshVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    parts.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, position)},
                        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, normal)},
                        {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(MeshVertex, color)}};
    // Opaque: the nearest surface wins, writes depth, and its colour as is.
    parts.depthStencil.depthTestEnable = VK_TRUE;
    parts.depthStencil.depthWriteEnable = VK_TRUE;
    parts.depthStencil.depthCompareOp = VK_COMPARE_OP_LESS;
    VkPipelineColorBlendAttachmentState blend{};
    blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                           VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    parts.blends = {blend, blend};
    parts.colorFormats = {ctx.formats().color, kMeshDistanceFormat};
    return gpu::createGraphicsPipeline(ctx, layout, parts);
}

} // namespace cutaway::render
