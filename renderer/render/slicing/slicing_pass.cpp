#include "render/slicing/slicing_pass.hpp"

#include "render/frame_image.hpp"
#include "render/skipping/operator_regions.hpp"
#include "shared/bindings.h"
#include "shared/tuning.h"

#include <algorithm>
#include <cstring>

namespace cutaway::render {
namespace {

// A render-pass attachment cleared at the start: colour to transparent black,
// depth to 1 and stencil to 0.
VkRenderingAttachmentInfo clearedAttachment(VkImageView view, VkImageLayout layout) {
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = view;
    a.imageLayout = layout;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    if (layout == VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL)
        a.clearValue.depthStencil = {1.0f, 0};
    else
        a.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    return a;
}

void toAttachment(VkCommandBuffer cmd, const gpu::Image& target) {
    gpu::transition(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
                    VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
}

void copyToReadback(VkCommandBuffer cmd, const gpu::Image& target, const gpu::Buffer& readback) {
    gpu::transition(
        cmd, target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
        VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = target.extent;
    vkCmdCopyImageToBuffer(cmd, target.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           readback.buffer.get(), 1, &region);
}

} // namespace

SlicingPass::SlicingPass(const PassResources& shared, VkDescriptorSetLayout operatorLayout)
    : m_shared(shared), m_saturation(shared.ctx, shared.nearest) {
    m_layout = gpu::createPipelineLayout(shared.ctx, {shared.frameLayout, operatorLayout});
}

void SlicingPass::ensureTargets(glm::uvec2 size, const ShaderVariant& variant) {
    const gpu::Context& ctx = m_shared.ctx;
    if (m_targetSize != size) {
        m_color = {};
        m_depthStencil = {};
        m_readback = {};
        m_aovs = {};
        m_aovReadbacks = {};
        m_targetSize = size;
    }
    const VkExtent3D extent{size.x, size.y, 1};
    const VkDeviceSize pixels = VkDeviceSize(size.x) * size.y;
    const VkDeviceSize texel = ctx.formats().color == VK_FORMAT_R32G32B32A32_SFLOAT ? 16 : 8;
    if (!m_color.image) {
        m_color =
            gpu::createImage(ctx, VK_IMAGE_TYPE_2D, ctx.formats().color, extent,
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                 VK_IMAGE_USAGE_SAMPLED_BIT);
        m_depthStencil = gpu::createImage(ctx, VK_IMAGE_TYPE_2D, ctx.formats().depthStencil, extent,
                                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                          VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT);
        m_readback = gpu::createBuffer(ctx, texel * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                       gpu::HostAccess::Read);
    }
    for (std::size_t t = 0; t + 1 < aovTargetCount(variant); ++t) {
        if (m_aovs[t].image) continue;
        m_aovs[t] =
            gpu::createImage(ctx, VK_IMAGE_TYPE_2D, ctx.formats().color, extent,
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        m_aovReadbacks[t] = gpu::createBuffer(ctx, texel * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                              gpu::HostAccess::Read);
    }
}

void SlicingPass::ensureVertexCapacity(std::size_t bytes) {
    if (m_vertices.buffer && m_vertices.size >= bytes) return;
    m_vertices = gpu::createBuffer(m_shared.ctx, std::max<std::size_t>(bytes * 3 / 2, 4096),
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, gpu::HostAccess::Write);
}

VkPipeline SlicingPass::pipelineFor(ShaderVariant variant, SliceProxy proxy) {
    // What only the ray caster reads would make another, identical pipeline;
    // the flavour is the one the layouts were made for.
    variant.census = false;
    variant.yieldLanes = false;
    variant.storageImages = m_shared.storageImages;
    const auto key = std::make_pair(variant, proxy);
    auto found = m_pipelines.find(key);
    if (found == m_pipelines.end())
        found = m_pipelines
                    .emplace(key, createSlicePipeline(m_shared.ctx, m_layout.get(), variant, proxy))
                    .first;
    return found->second.get();
}

std::vector<Proxy> SlicingPass::proxies(const Frame& frame) {
    // An operator's box is a stencil-only proxy, its shader runs on its
    // regions; the volume's proxies are its occupied bricks (empty-space
    // skipping).
    std::vector<Proxy> proxies;
    m_roles.clear();
    EmptySpace& space = m_shared.emptySpace;
    const auto& ops = m_shared.operators.operators();
    for (std::size_t i = 0; i < ops.size(); ++i) {
        const GpuOperator& op = *ops[i];
        const int index = static_cast<int>(i);
        proxies.push_back(orientedBoxProxy(op.box.localToWorld, op.box.local.lo, op.box.local.hi));
        if (!space.operatorSkipping()) {
            m_roles.push_back({index, false});
            continue;
        }
        const std::vector<operators::LocalBox>& regions =
            space.regionBoxes(i, op, frame.geometry.reachMm);
        if (coverage(regions, op.box.local) > kWholeBoxCoverage) { // not worth a stencil pass
            m_roles.push_back({index, false});
            continue;
        }
        m_roles.push_back({index, true});
        for (const operators::LocalBox& r : regions) {
            proxies.push_back(orientedBoxProxy(op.box.localToWorld, r.lo, r.hi));
            m_roles.push_back({index, false});
        }
    }
    for (const Box& box : space.occupiedBoxes()) {
        proxies.push_back(boxProxy(box));
        m_roles.push_back({});
    }
    return proxies;
}

Image SlicingPass::render(const Frame& frame, FrameStats& stats) {
    const gpu::Context& ctx = m_shared.ctx;
    const FrameGeometry& g = frame.geometry;
    const CameraMatrices& cam = g.camera;
    const double minDepth = cam.perspective ? cam.nearPlane : -1e30;
    const SliceSet slices = buildSlices(proxies(frame), cam.eye, cam.forward, g.sliceMm, minDepth);
    stats.slices = slices.sliceCount;
    stats.vertices = slices.triangles.size();
    const std::size_t vertexBytes = slices.triangles.size() * sizeof(glm::vec3);
    ensureVertexCapacity(vertexBytes);
    if (vertexBytes) std::memcpy(m_vertices.mapped, slices.triangles.data(), vertexBytes);
    ensureTargets(frame.size, frame.variant);

    const bool storage = frame.inputs.storageImages;
    gpu::DescriptorSet set =
        gpu::allocateDescriptorSet(ctx, m_shared.frameLayout,
                                   {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                    {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, storage ? 3u : 0u}});
    writeFrameInputs(ctx, set.set, frame.inputs);
    const gpu::DescriptorSet saturationSet = m_saturation.bind(m_color);
    ctx.submitAndWait(
        [&](VkCommandBuffer cmd) { record(cmd, frame, slices, set.set, saturationSet.set); });
    return readBack(frame);
}

void SlicingPass::record(VkCommandBuffer cmd, const Frame& frame, const SliceSet& slices,
                         VkDescriptorSet frameSet, VkDescriptorSet saturationSet) {
    std::vector<const gpu::Image*> targets{&m_color};
    for (std::size_t t = 0; t + 1 < aovTargetCount(frame.variant); ++t)
        targets.push_back(&m_aovs[t]);
    for (const gpu::Image* target : targets)
        toAttachment(cmd, *target);
    const MeshTargets* meshes = frame.meshes;
    if (meshes) {
        toAttachment(cmd, meshes->color);
        toAttachment(cmd, meshes->distance);
    }
    gpu::transition(cmd, m_depthStencil, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
                    VK_ACCESS_2_NONE,
                    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                        VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    if (meshes)
        m_shared.meshes.recordPass(cmd, frameSet, meshes->color, meshes->distance, m_depthStencil);

    VkRenderingAttachmentInfo colors[4];
    for (std::size_t t = 0; t < targets.size(); ++t)
        colors[t] =
            clearedAttachment(targets[t]->view.get(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    VkRenderingAttachmentInfo ds = clearedAttachment(
        m_depthStencil.view.get(), VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    VkRenderingAttachmentInfo depth = ds; // the meshes' depth, when there are any
    if (meshes) depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {m_color.extent.width, m_color.extent.height}};
    info.layerCount = 1;
    info.colorAttachmentCount = static_cast<uint32_t>(targets.size());
    info.pColorAttachments = colors;
    info.pDepthAttachment = &depth;
    info.pStencilAttachment = &ds;
    const VkViewport viewport{
        0.0f, 0.0f, static_cast<float>(frame.size.x), static_cast<float>(frame.size.y), 0.0f, 1.0f};
    // Chunks of slices; between two, the saturation pass marks opaque
    // pixels so the slices behind them are not shaded (early termination).
    const std::size_t count = slices.slices.size();
    const auto chunk = static_cast<std::size_t>(shader::kSlicesPerChunk);
    for (std::size_t begin = 0; begin < std::max<std::size_t>(count, 1); begin += chunk) {
        if (begin > 0) {
            m_saturation.record(cmd, saturationSet, m_color, m_depthStencil,
                                static_cast<float>(frame.scene.render.terminationOpacity));
            for (std::size_t t = 0; t < targets.size(); ++t)
                colors[t].loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
            depth.loadOp = ds.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
        }
        vkCmdBeginRendering(cmd, &info);
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &info.renderArea);
        if (count)
            recordSlices(cmd, slices, frameSet, frame.variant, begin,
                         std::min(count, begin + chunk));
        vkCmdEndRendering(cmd);
    }
    copyToReadback(cmd, m_color, m_readback);
    for (std::size_t t = 0; t + 1 < targets.size(); ++t)
        copyToReadback(cmd, m_aovs[t], m_aovReadbacks[t]);
    if (meshes) {
        copyToReadback(cmd, meshes->color, meshes->colorReadback);
        copyToReadback(cmd, meshes->distance, meshes->distanceReadback);
    }
    gpu::barrierTransferToHost(cmd);
}

void SlicingPass::clearStencil(VkCommandBuffer cmd) const {
    VkClearAttachment clear{VK_IMAGE_ASPECT_STENCIL_BIT, 0, {}};
    clear.clearValue.depthStencil = {1.0f, 0};
    VkClearRect rect{{{0, 0}, {m_color.extent.width, m_color.extent.height}}, 0, 1};
    vkCmdClearAttachments(cmd, 1, &clear, 1, &rect);
}

void SlicingPass::recordSlices(VkCommandBuffer cmd, const SliceSet& slices,
                               VkDescriptorSet frameSet, const ShaderVariant& variant,
                               std::size_t begin, std::size_t end) {
    const VkPipeline background = pipelineFor(variant, SliceProxy::Background);
    const auto& ops = m_shared.operators.operators();
    std::vector<VkPipeline> operatorPipelines; // by the operator's alignment
    for (const auto& op : ops) {
        ShaderVariant v = variant;
        v.alignment = alignmentCode(op->spec.alignment.mode);
        operatorPipelines.push_back(pipelineFor(v, SliceProxy::Operator));
    }
    VkDeviceSize offset = 0;
    VkBuffer vb = m_vertices.buffer.get();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_layout.get(), 0, 1, &frameSet,
                            0, nullptr);
    if (ops.empty()) { // one draw: nothing to composite, the slices are consecutive
        uint32_t first = UINT32_MAX, last = 0;
        for (std::size_t k = begin; k < end; ++k) {
            for (const SliceDraw& d : slices.slices[k]) {
                first = std::min(first, d.first);
                last = std::max(last, d.first + d.count);
            }
        }
        if (first >= last) return;
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, background);
        vkCmdSetStencilReference(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 1);
        vkCmdDraw(cmd, last - first, 1, first, 0);
        return;
    }
    const VkPipeline stencil = pipelineFor(variant, SliceProxy::OperatorStencil);
    for (std::size_t k = begin; k < end; ++k) {
        // Stencil references cycle through 1..255; before a value comes back,
        // clear the stencil so an old slice's mark cannot hide the background.
        if (k > 0 && k % 255 == 0) clearStencil(cmd);
        vkCmdSetStencilReference(cmd, VK_STENCIL_FACE_FRONT_AND_BACK,
                                 static_cast<uint32_t>(k % 255 + 1));
        // Operators first (each its stencil box, then its regions: consecutive
        // polygons of one kind are one draw); the volume's boxes follow.
        const std::vector<SliceDraw>& draws = slices.slices[k];
        uint32_t first = UINT32_MAX, last = 0;
        for (std::size_t i = 0; i < draws.size();) {
            const ProxyRole role = m_roles[static_cast<std::size_t>(draws[i].proxy)];
            if (role.op < 0) {
                first = std::min(first, draws[i].first);
                last = std::max(last, draws[i].first + draws[i].count);
                ++i;
                continue;
            }
            const uint32_t start = draws[i].first;
            uint32_t stop = start + draws[i].count;
            for (++i; i < draws.size(); ++i) {
                const ProxyRole next = m_roles[static_cast<std::size_t>(draws[i].proxy)];
                if (next.op != role.op || next.stencil != role.stencil || draws[i].first != stop)
                    break;
                stop += draws[i].count;
            }
            const auto op = static_cast<std::size_t>(role.op);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                              role.stencil ? stencil : operatorPipelines[op]);
            VkDescriptorSet set = ops[op]->set.set;
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_layout.get(), 1, 1,
                                    &set, 0, nullptr);
            vkCmdDraw(cmd, stop - start, 1, start, 0);
        }
        if (first < last) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, background);
            vkCmdDraw(cmd, last - first, 1, first, 0);
        }
    }
}

Image SlicingPass::readBack(const Frame& frame) const {
    const int width = static_cast<int>(frame.size.x), height = static_cast<int>(frame.size.y);
    Image image = readImage(m_shared.ctx, m_readback, width, height);
    if (!frame.variant.withAovs) return image;
    std::array<std::vector<float>, 3> texels;
    for (std::size_t t = 0; t + 1 < aovTargetCount(frame.variant); ++t)
        texels[t] = readColorTexels(m_shared.ctx, m_aovReadbacks[t], image.rgba.size());
    const AovTexels aovs{texels[0].data(), {texels[1].data(), texels[2].data()}};
    readAovs(frame.scene.output, aovs, image);
    return image;
}

} // namespace cutaway::render
