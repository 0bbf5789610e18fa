// SliceRenderer's ray-cast frames (render.method "raycast"): the meshes first,
// then the Raycaster's pass over the volume and the operators; the class and
// the frame set-up they share with slicing are in slice_renderer.{hpp,cpp}.
#include "render/ray_cells.hpp"
#include "render/slice_renderer.hpp"
#include "shared/frame.h"

#include <cstring>

namespace cutaway::render {

VkImageView SliceRenderer::blocksFor(std::size_t index, const GpuOperator& op, double reachMm) {
    const auto distances = [&](glm::ivec3 dims, const std::vector<uint8_t>& active) {
        const std::vector<uint8_t> d = chessboardDistance(dims, active);
        const glm::uvec3 n(dims);
        return gpu::createStorageVolume(m_ctx, VK_FORMAT_R8_UINT, {n.x, n.y, n.z}, d.data(),
                                        d.size(), VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    };
    if (!m_operatorSkipping) { // one active block over the whole box
        if (!m_noSkipping.image) m_noSkipping = distances(glm::ivec3(1), {1});
        return m_noSkipping.view.get();
    }
    Regions& regions = regionsFor(index, op, reachMm);
    if (!regions.distance.image) {
        const OperatorBlocks blocks = operatorBlocks(op.spec, op.box, casesFor(op), reachMm);
        regions.distance = distances(blocks.dims, blocks.active);
    }
    return regions.distance.view.get();
}

Image SliceRenderer::renderRaycast(const CameraMatrices& cam, const GpuVolume& volume,
                                   const gpu::Image& transfer, const SliceVariant& variant,
                                   int marginVoxels, double reachMm, VkDescriptorSet frameSet) {
    const uint32_t width = m_targetSize.x, height = m_targetSize.y;
    const bool withMeshes = !m_meshes->empty();
    // The meshes' depth ends the rays: a depth-stencil target the rays can
    // sample (the slicing one need not be), or a 1 everywhere without meshes.
    if (withMeshes && (!m_rayDepth.image || m_rayDepth.extent.width != width ||
                       m_rayDepth.extent.height != height)) {
        m_rayDepth = gpu::createImage(
            m_ctx, VK_IMAGE_TYPE_2D, m_ctx.formats().depthStencil, {width, height, 1},
            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
            VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT);
        m_rayDepthView = gpu::createAspectView(m_ctx, m_rayDepth, VK_IMAGE_ASPECT_DEPTH_BIT);
    }
    if (!withMeshes && !m_noMeshDepth.image) {
        m_noMeshDepth =
            gpu::createImage(m_ctx, VK_IMAGE_TYPE_2D, VK_FORMAT_R32_SFLOAT, {1, 1, 1},
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        const float far = 1.0f;
        gpu::uploadImage(m_ctx, m_noMeshDepth, &far, sizeof far,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    }
    if (!m_rayTarget.image || m_rayTarget.extent.width != width ||
        m_rayTarget.extent.height != height) {
        m_rayTarget = gpu::createImage(
            m_ctx, VK_IMAGE_TYPE_2D, VK_FORMAT_R32G32B32A32_SFLOAT, {width, height, 1},
            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        m_rayReadback = gpu::createBuffer(m_ctx, 16ull * width * height,
                                          VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::HostAccess::Read);
        m_rayId =
            gpu::createImage(m_ctx, VK_IMAGE_TYPE_2D, VK_FORMAT_R32_SFLOAT, {width, height, 1},
                             VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        m_rayIdReadback = gpu::createBuffer(
            m_ctx, 4ull * width * height, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::HostAccess::Read);
    }
    m_raycaster->prepareCells(volume, m_cellSpans ? &*m_cellSpans : nullptr, *m_visible,
                              m_occupancySerial, marginVoxels);
    std::vector<Raycaster::Operator> operators;
    const auto& ops = m_operators->operators();
    for (std::size_t i = 0; i < ops.size(); ++i) {
        const GpuOperator& op = *ops[i];
        operators.push_back({op.set.set, blocksFor(i, op, reachMm),
                             static_cast<const shader::OperatorUniforms*>(op.uniforms.mapped),
                             alignmentCode(op.spec.alignment.mode), op.box});
    }
    const Raycaster::Inputs inputs{m_uniforms.buffer.get(),
                                   sizeof(shader::FrameUniforms),
                                   volume.values.view.get(),
                                   valueImages(volume),
                                   volume.gradients.view.get(),
                                   transfer.view.get(),
                                   m_classes.view.get(),
                                   withMeshes ? m_rayDepthView.get() : m_noMeshDepth.view.get(),
                                   withMeshes ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                              : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const Raycaster::Targets targets{m_rayTarget, m_rayId};
    const gpu::DescriptorSet set = m_raycaster->bind(inputs, targets, operators);
    const bool withId = variant.withOperatorId;
    SliceVariant rays = variant; // the rays always write the ids; the copy is what costs
    rays.withOperatorId = false;
    m_ctx.submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = m_rayTarget.extent;
        if (withMeshes) { // first the meshes, opaque, with their depth
            gpu::transition(cmd, m_meshColor, VK_IMAGE_LAYOUT_UNDEFINED,
                            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
                            VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
            gpu::transition(cmd, m_rayDepth, VK_IMAGE_LAYOUT_UNDEFINED,
                            VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                            VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                            VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                                VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                            VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
            m_meshes->recordPass(cmd, frameSet, m_meshColor, m_rayDepth);
            gpu::transition(cmd, m_rayDepth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                            VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
                            VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                            VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
            gpu::transition(cmd, m_meshColor, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                            VK_ACCESS_2_TRANSFER_READ_BIT);
            vkCmdCopyImageToBuffer(cmd, m_meshColor.image.get(),
                                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   m_meshReadback.buffer.get(), 1, &region);
        }
        m_raycaster->record(cmd, set.set, targets, cam, rays, operators, m_operatorSkipping);
        vkCmdCopyImageToBuffer(cmd, m_rayTarget.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               m_rayReadback.buffer.get(), 1, &region);
        if (withId)
            vkCmdCopyImageToBuffer(cmd, m_rayId.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   m_rayIdReadback.buffer.get(), 1, &region);
        gpu::barrierTransferToHost(cmd);
    });
    Image image(static_cast<int>(width), static_cast<int>(height));
    std::memcpy(image.rgba.data(), m_rayReadback.mapped, image.rgba.size() * sizeof(float));
    if (withId) {
        const auto* codes = static_cast<const float*>(m_rayIdReadback.mapped);
        image.operatorIds.resize(image.rgba.size() / 4);
        for (std::size_t p = 0; p < image.operatorIds.size(); ++p)
            image.operatorIds[p] = operatorIdOf(codes[p], codes[p] > 0.5f);
    }
    if (withMeshes) compositeMeshes(image);
    return image;
}

} // namespace cutaway::render
