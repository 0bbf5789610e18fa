#include "render/mesh_pass.hpp"

#include "gpu/pipeline.hpp"
#include "render/mesh_pipeline.hpp"
#include "shared/mesh_draw.h"

#include <cstring>

namespace cutaway::render {
namespace {

// The world box of a model box [lo, hi] under `m`: the hull of its 8 corners.
Box transformedBounds(const glm::dmat4& m, glm::vec3 lo, glm::vec3 hi) {
    Box box{glm::dvec3(1e300), glm::dvec3(-1e300)};
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                           (corner & 4) ? hi.z : lo.z);
        const glm::dvec3 w = glm::dvec3(m * glm::dvec4(p, 1.0));
        box.lo = glm::min(box.lo, w);
        box.hi = glm::max(box.hi, w);
    }
    return box;
}

} // namespace

glm::dmat4 operatorFrame(const glm::dmat4& localToWorld) {
    // Gram-Schmidt on the box axes: a placement matrix may carry a little shear.
    const glm::dvec3 x = glm::normalize(glm::dvec3(localToWorld[0]));
    glm::dvec3 y = glm::dvec3(localToWorld[1]);
    y = glm::normalize(y - glm::dot(y, x) * x);
    glm::dvec3 z = glm::cross(x, y);
    if (glm::dot(z, glm::dvec3(localToWorld[2])) < 0.0) z = -z; // keep a mirrored box mirrored
    glm::dmat4 frame(1.0);
    frame[0] = glm::dvec4(x, 0.0);
    frame[1] = glm::dvec4(y, 0.0);
    frame[2] = glm::dvec4(z, 0.0);
    frame[3] = localToWorld[3];
    return frame;
}

MeshPass::MeshPass(const gpu::Context& ctx, VkDescriptorSetLayout frameLayout) : m_ctx(ctx) {
    m_layout = gpu::createPipelineLayout(ctx, std::vector<VkDescriptorSetLayout>{frameLayout},
                                         sizeof(shader::MeshDraw), VK_SHADER_STAGE_VERTEX_BIT);
}

void MeshPass::upload(GpuMesh& gpuMesh, const mesh::TriangleMesh& mesh, bool reuse) {
    std::vector<MeshVertex> vertices(mesh.positions.size());
    for (std::size_t i = 0; i < vertices.size(); ++i)
        vertices[i] = {mesh.positions[i], mesh.normals[i], mesh.colors[i]};
    const std::size_t vertexBytes = vertices.size() * sizeof(MeshVertex);
    const std::size_t indexBytes = mesh.indices.size() * sizeof(uint32_t);
    // Host-visible: tool meshes are small, and glyphs change every frame.
    if (!reuse || gpuMesh.vertices.size < vertexBytes)
        gpuMesh.vertices =
            gpu::createBuffer(m_ctx, std::max<std::size_t>(vertexBytes, 64),
                              VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, gpu::HostAccess::Write);
    if (!reuse || gpuMesh.indices.size < indexBytes)
        gpuMesh.indices =
            gpu::createBuffer(m_ctx, std::max<std::size_t>(indexBytes, 64),
                              VK_BUFFER_USAGE_INDEX_BUFFER_BIT, gpu::HostAccess::Write);
    if (vertexBytes) std::memcpy(gpuMesh.vertices.mapped, vertices.data(), vertexBytes);
    if (indexBytes) std::memcpy(gpuMesh.indices.mapped, mesh.indices.data(), indexBytes);
    gpuMesh.indexCount = static_cast<uint32_t>(mesh.indices.size());
    gpuMesh.lo = mesh.lo;
    gpuMesh.hi = mesh.hi;
}

std::optional<Box> MeshPass::prepare(const Scene& scene, double volumeDiagonal) {
    m_draws.clear();
    std::optional<Box> bounds;
    const auto add = [&](const GpuMesh& gpuMesh, const glm::dmat4& m,
                         std::optional<glm::vec3> color) {
        if (gpuMesh.indexCount == 0) return;
        m_draws.push_back({&gpuMesh, m, color});
        const Box b = transformedBounds(m, gpuMesh.lo, gpuMesh.hi);
        if (!bounds) bounds = b;
        bounds->lo = glm::min(bounds->lo, b.lo);
        bounds->hi = glm::max(bounds->hi, b.hi);
    };
    for (const MeshSpec& spec : scene.meshes) {
        const std::string key = spec.file.string();
        auto it = m_models.find(key);
        if (it == m_models.end()) {
            const mesh::TriangleMesh model = mesh::loadGltf(spec.file); // InputError if bad
            it = m_models.emplace(key, GpuMesh{}).first;
            upload(it->second, model, false);
        }
        glm::dmat4 parent(1.0);
        if (spec.attach)
            parent =
                operatorFrame(scene.operators[static_cast<std::size_t>(*spec.attach)].localToWorld);
        add(it->second, parent * spec.placement, spec.color);
    }
    // Glyphs: each box outline built in world space, all in one buffer.
    mesh::TriangleMesh glyphs;
    for (const OperatorSpec& op : scene.operators) {
        if (!op.glyph.enabled) continue;
        const glm::dmat4 frame = operatorFrame(op.localToWorld);
        const glm::dvec3 half(glm::length(glm::dvec3(op.localToWorld[0])),
                              glm::length(glm::dvec3(op.localToWorld[1])),
                              glm::length(glm::dvec3(op.localToWorld[2])));
        const double width = op.glyph.width > 0.0 ? op.glyph.width : volumeDiagonal / 300.0;
        mesh::TriangleMesh box =
            mesh::boxOutline(glm::vec3(-half), glm::vec3(half), static_cast<float>(width),
                             glm::vec4(op.glyph.color, 1.0f));
        const glm::dmat3 rotation(frame);
        for (glm::vec3& p : box.positions)
            p = glm::vec3(frame * glm::dvec4(glm::dvec3(p), 1.0));
        for (glm::vec3& n : box.normals)
            n = glm::vec3(rotation * glm::dvec3(n));
        glyphs.append(box);
    }
    if (!glyphs.indices.empty()) {
        upload(m_glyphs, glyphs, true);
        add(m_glyphs, glm::dmat4(1.0), std::nullopt);
    }
    return bounds;
}

void MeshPass::record(VkCommandBuffer cmd, VkDescriptorSet frameSet) {
    if (empty()) return;
    if (!m_pipeline) m_pipeline = createMeshPipeline(m_ctx, m_layout.get());
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_layout.get(), 0, 1, &frameSet,
                            0, nullptr);
    for (const Draw& d : m_draws) {
        shader::MeshDraw push{};
        push.modelToWorld = glm::mat4(d.modelToWorld);
        const glm::mat3 normal = glm::transpose(glm::inverse(glm::mat3(d.modelToWorld)));
        push.normal0 = glm::vec4(normal[0], 0.0f);
        push.normal1 = glm::vec4(normal[1], 0.0f);
        push.normal2 = glm::vec4(normal[2], 0.0f);
        push.color = d.color ? glm::vec4(*d.color, 1.0f) : glm::vec4(0.0f);
        vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
        VkDeviceSize offset = 0;
        VkBuffer vb = d.mesh->vertices.buffer.get();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
        vkCmdBindIndexBuffer(cmd, d.mesh->indices.buffer.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, d.mesh->indexCount, 1, 0, 0, 0);
    }
}

void MeshPass::recordPass(VkCommandBuffer cmd, VkDescriptorSet frameSet, const gpu::Image& color,
                          const gpu::Image& distance, const gpu::Image& depthStencil) {
    VkRenderingAttachmentInfo targets[2]{{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO}};
    VkRenderingAttachmentInfo& target = targets[0];
    target.imageView = color.view.get();
    target.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    target.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR; // transparent black where no mesh is
    target.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    targets[1] = target;
    targets[1].imageView = distance.view.get();
    VkRenderingAttachmentInfo depth = target;
    depth.imageView = depthStencil.view.get();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {color.extent.width, color.extent.height}};
    info.layerCount = 1;
    info.colorAttachmentCount = 2;
    info.pColorAttachments = targets;
    info.pDepthAttachment = &depth;
    info.pStencilAttachment = &depth;
    vkCmdBeginRendering(cmd, &info);
    VkViewport viewport{
        0.0f, 0.0f, float(info.renderArea.extent.width), float(info.renderArea.extent.height),
        0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &info.renderArea);
    record(cmd, frameSet);
    vkCmdEndRendering(cmd);
    // The volume pass tests (and its stencil writes) after the meshes' depth writes.
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask =
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    barrier.dstStageMask = barrier.srcStageMask;
    barrier.dstAccessMask = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                            VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

} // namespace cutaway::render
