#include "render/raycast/raycast_pass.hpp"

#include "render/frame_image.hpp"
#include "shared/frame.h"

#include <cstring>
#include <utility>

namespace cutaway::render {

RaycastPass::RaycastPass(const PassResources& shared, VkDescriptorSetLayout operatorLayout,
                         const gpu::DeviceTuning& tuning)
    : m_shared(shared),
      m_raycaster(shared.ctx, shared.linear, shared.nearest, operatorLayout, tuning) {}

void RaycastPass::ensureTargets(glm::uvec2 size, bool withMeshes, bool withMattes) {
    const gpu::Context& ctx = m_shared.ctx;
    if (m_targetSize != size) {
        m_target = {};
        m_readback = {};
        m_id = {};
        m_idReadback = {};
        m_mattes = {};
        m_mattesReadback = {};
        m_depthView = {};
        m_depth = {};
        m_targetSize = size;
    }
    const VkExtent3D extent{size.x, size.y, 1};
    const VkDeviceSize pixels = VkDeviceSize(size.x) * size.y;
    // The meshes' depth ends the rays: a depth-stencil target the rays can
    // sample (the slicing one need not be), or a 1 everywhere without meshes.
    if (withMeshes && !m_depth.image) {
        m_depth = gpu::createImage(ctx, VK_IMAGE_TYPE_2D, ctx.formats().depthStencil, extent,
                                   VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                       VK_IMAGE_USAGE_SAMPLED_BIT,
                                   VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT);
        m_depthView = gpu::createAspectView(ctx, m_depth, VK_IMAGE_ASPECT_DEPTH_BIT);
    }
    if (!withMeshes && !m_noMeshDepth.image) {
        m_noMeshDepth =
            gpu::createImage(ctx, VK_IMAGE_TYPE_2D, VK_FORMAT_R32_SFLOAT, {1, 1, 1},
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        m_noMeshDepth.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        const float far = 1.0f;
        gpu::uploadImage(ctx, m_noMeshDepth, &far, sizeof far, m_noMeshDepth.layout,
                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    }
    if (!m_target.image) {
        const auto usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        m_target =
            gpu::createImage(ctx, VK_IMAGE_TYPE_2D, VK_FORMAT_R32G32B32A32_SFLOAT, extent, usage);
        m_readback = gpu::createBuffer(ctx, 16 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                       gpu::HostAccess::Read);
        m_id =
            gpu::createImage(ctx, VK_IMAGE_TYPE_2D, VK_FORMAT_R32G32B32A32_SFLOAT, extent, usage);
        m_idReadback = gpu::createBuffer(ctx, 16 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                         gpu::HostAccess::Read);
    }
    // The mattes' image, full size only while frames ask for mattes.
    const VkExtent2D mattes = withMattes ? VkExtent2D{size.x, size.y} : VkExtent2D{1, 1};
    if (!m_mattes.image || m_mattes.extent.width != mattes.width ||
        m_mattes.extent.height != mattes.height) {
        m_mattes =
            gpu::createImageArray(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, mattes, 2,
                                  VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        m_mattesReadback =
            gpu::createBuffer(ctx, 32 * VkDeviceSize(mattes.width) * mattes.height,
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::HostAccess::Read);
    }
}

void RaycastPass::recordMeshes(VkCommandBuffer cmd, const Frame& frame, VkDescriptorSet frameSet) {
    const MeshTargets& meshes = *frame.meshes;
    for (const gpu::Image* target : {&meshes.color, &meshes.distance})
        gpu::transition(cmd, *target, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
                        VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    gpu::transition(
        cmd, m_depth, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
        VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    m_shared.meshes.recordPass(cmd, frameSet, meshes.color, meshes.distance, m_depth);
    gpu::transition(cmd, m_depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    const std::pair<const gpu::Image*, const gpu::Buffer*> copies[] = {
        {&meshes.color, &meshes.colorReadback}, {&meshes.distance, &meshes.distanceReadback}};
    for (const auto& [target, readback] : copies) {
        gpu::transition(cmd, *target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                        VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = target->extent;
        vkCmdCopyImageToBuffer(cmd, target->image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               readback->buffer.get(), 1, &region);
    }
}

Image RaycastPass::render(const Frame& frame, FrameStats& stats) {
    const gpu::Context& ctx = m_shared.ctx;
    const bool withMeshes = frame.meshes != nullptr;
    const bool withMattes = frame.variant.withAovs && frame.variant.mattes;
    ensureTargets(frame.size, withMeshes, withMattes);
    stats.slices = 0;
    stats.vertices = 0;
    EmptySpace& space = m_shared.emptySpace;
    const FrameGeometry& g = frame.geometry;
    m_raycaster.prepareCells(frame.volume, space.cellSpans(), space.visible(),
                             space.occupancySerial(), g.marginVoxels);
    std::vector<Raycaster::Operator> operators;
    const auto& ops = m_shared.operators.operators();
    for (std::size_t i = 0; i < ops.size(); ++i) {
        const GpuOperator& op = *ops[i];
        operators.push_back({op.set.set, space.blockDistances(i, op, g.reachMm),
                             static_cast<const shader::OperatorUniforms*>(op.uniforms.mapped),
                             alignmentCode(op.spec.alignment.mode), op.box});
    }
    // The meshes' pass reads the slicing set 0 (the frame's uniforms).
    gpu::DescriptorSet meshSet;
    if (withMeshes) {
        meshSet = gpu::allocateDescriptorSet(
            ctx, m_shared.frameLayout,
            {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
             {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4},
             {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, frame.inputs.storageImages ? 3u : 0u}});
        writeFrameInputs(ctx, meshSet.set, frame.inputs);
    }
    const Raycaster::Targets targets{m_target, m_id, m_mattes};
    const Raycaster::MeshDepth depth{withMeshes ? m_depthView.get() : m_noMeshDepth.view.get(),
                                     withMeshes ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                                : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const gpu::DescriptorSet set = m_raycaster.bind(frame.inputs, depth, targets, operators);
    ShaderVariant rays = frame.variant; // the rays always write the ids; the copy is what costs
    rays.withAovs = false;
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        if (withMeshes) recordMeshes(cmd, frame, meshSet.set); // first the meshes, opaque
        m_raycaster.record(cmd, set.set, targets, g.camera, rays, operators,
                           m_shared.emptySpace.operatorSkipping());
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = m_target.extent;
        vkCmdCopyImageToBuffer(cmd, m_target.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               m_readback.buffer.get(), 1, &region);
        if (frame.variant.withAovs)
            vkCmdCopyImageToBuffer(cmd, m_id.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   m_idReadback.buffer.get(), 1, &region);
        if (withMattes) {
            region.imageSubresource.layerCount = 2;
            vkCmdCopyImageToBuffer(cmd, m_mattes.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   m_mattesReadback.buffer.get(), 1, &region);
        }
        gpu::barrierTransferToHost(cmd);
    });
    return readBack(frame);
}

Image RaycastPass::readBack(const Frame& frame) const {
    Image image(static_cast<int>(frame.size.x), static_cast<int>(frame.size.y));
    std::memcpy(image.rgba.data(), m_readback.mapped, image.rgba.size() * sizeof(float));
    if (!frame.variant.withAovs) return image;
    const auto* mattes = static_cast<const float*>(m_mattesReadback.mapped);
    const std::size_t layer = image.rgba.size();
    const AovTexels aovs{static_cast<const float*>(m_idReadback.mapped), {mattes, mattes + layer}};
    readAovs(frame.scene.output, aovs, image);
    return image;
}

} // namespace cutaway::render
