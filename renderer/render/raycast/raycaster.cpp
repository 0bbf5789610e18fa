#include "render/raycast/raycaster.hpp"

#include "raycast_comp.spv.h"
#include "raycast_lanes_comp.spv.h"
#include "raycast_operator_comp.spv.h"
#include "raycast_operator_lanes_comp.spv.h"
#include "raycast_operator_storage_comp.spv.h"
#include "raycast_operator_storage_lanes_comp.spv.h"
#include "raycast_operators_comp.spv.h"
#include "raycast_operators_lanes_comp.spv.h"
#include "raycast_operators_storage_comp.spv.h"
#include "raycast_operators_storage_lanes_comp.spv.h"
#include "raycast_storage_comp.spv.h"
#include "raycast_storage_lanes_comp.spv.h"
#include "render/skipping/ray_cells.hpp"
#include "shared/bindings.h"
#include "shared/tile_order.h"
#include "shared/visible_runs.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace cutaway::render {

using shader::RayPush;

namespace {

std::uint32_t packTile(glm::uvec2 tile) {
    return tile.x | (tile.y << 16);
}

// The world corners of the operators' deformed boxes.
std::vector<glm::dvec3> boxCorners(const std::vector<Raycaster::Operator>& operators) {
    std::vector<glm::dvec3> corners;
    for (const Raycaster::Operator& op : operators)
        for (const glm::dvec3& c : op.box.corners())
            corners.push_back(c);
    return corners;
}

} // namespace

TileRect tilesCovering(const glm::dmat4& viewProj, const std::vector<glm::dvec3>& points,
                       glm::uvec2 pixels) {
    const glm::uvec2 tiles = (pixels + 7u) / 8u;
    const TileRect all{glm::uvec2(0), tiles};
    if (points.empty()) return {};
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : points) {
        const glm::dvec4 clip = viewProj * glm::dvec4(p, 1.0);
        if (!(clip.w > 1e-9)) return all; // at or behind the eye: no bounds on the screen
        const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
        lo = glm::min(lo, ndc);
        hi = glm::max(hi, ndc);
    }
    // Pixel i's ray passes through ndc (i + 0.5) / size * 2 - 1 (ray_march.h).
    const glm::dvec2 size(pixels);
    const glm::dvec2 pixelLo = glm::floor((lo + 1.0) * 0.5 * size - 0.5) - 1.0;
    const glm::dvec2 pixelHi = glm::ceil((hi + 1.0) * 0.5 * size - 0.5) + 1.0;
    const glm::dvec2 tileLo =
        glm::clamp(glm::floor(pixelLo / 8.0), glm::dvec2(0.0), glm::dvec2(tiles));
    const glm::dvec2 tileHi =
        glm::clamp(glm::floor(pixelHi / 8.0) + 1.0, glm::dvec2(0.0), glm::dvec2(tiles));
    TileRect rect{glm::uvec2(tileLo), glm::uvec2(tileHi)};
    return rect.empty() ? TileRect{} : rect;
}

Raycaster::Raycaster(const gpu::Context& ctx, VkSampler linear, VkSampler nearest,
                     VkDescriptorSetLayout operatorSetLayout, const gpu::DeviceTuning& tuning)
    : m_ctx(ctx), m_storageImages(tuning.storageImages()), m_linear(linear), m_nearest(nearest) {
    const auto cs = VK_SHADER_STAGE_COMPUTE_BIT;
    // The cells and blocks are storage images: the rays read one texel at
    // every sample, and on lavapipe imageLoad is an inline load where a
    // sampled texelFetch is a call (docs/design/lavapipe.md#what-a-fetch-costs).
    const auto storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    const auto buffer = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    std::vector<VkDescriptorSetLayoutBinding> bindings =
        frameInputBindings(cs, cs, m_storageImages);
    for (uint32_t b : {CW_BIND_RAY_TARGET, CW_BIND_RAY_CELLS, CW_BIND_RAY_ID, CW_BIND_RAY_MATTES})
        bindings.push_back({b, storage, 1, cs, nullptr});
    for (uint32_t i = 0; i < CW_RAY_MAX_OPERATORS; ++i)
        bindings.push_back({CW_BIND_RAY_BLOCKS + i, storage, 1, cs, nullptr});
    bindings.push_back({CW_BIND_RAY_OPERATORS, buffer, 1, cs, nullptr});
    bindings.push_back({CW_BIND_RAY_VISIBLE, buffer, 1, cs, nullptr});
    bindings.push_back(
        {CW_BIND_RAY_MESH_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr});
    m_setLayout = gpu::createSetLayout(ctx, bindings, "ray caster frame");
    m_layout = gpu::createPipelineLayout(ctx, m_setLayout.get(), sizeof(RayPush), cs);
    std::vector<VkDescriptorSetLayout> sets(1 + CW_RAY_MAX_OPERATORS, operatorSetLayout);
    sets[0] = m_setLayout.get();
    m_operatorLayout = gpu::createPipelineLayout(ctx, sets, sizeof(RayPush), cs);
    m_operatorUniforms =
        gpu::createBuffer(ctx, sizeof(shader::OperatorUniforms) * CW_RAY_MAX_OPERATORS,
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::HostAccess::Write);
}

gpu::DescriptorSet Raycaster::bind(const FrameInputs& in, const MeshDepth& meshDepth,
                                   const Targets& targets,
                                   const std::vector<Operator>& operators) const {
    const auto storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    gpu::DescriptorSet set = gpu::allocateDescriptorSet(
        m_ctx, m_setLayout.get(),
        {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 5},
         {storage, 4 + CW_RAY_MAX_OPERATORS + (m_storageImages ? 3u : 0u)},
         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2}});
    writeFrameInputs(m_ctx, set.set, in);
    gpu::writeImageDescriptor(m_ctx, set.set, CW_BIND_RAY_TARGET, storage, targets.color.view.get(),
                              VK_IMAGE_LAYOUT_GENERAL);
    gpu::writeImageDescriptor(m_ctx, set.set, CW_BIND_RAY_ID, storage, targets.id.view.get(),
                              VK_IMAGE_LAYOUT_GENERAL);
    gpu::writeImageDescriptor(m_ctx, set.set, CW_BIND_RAY_MATTES, storage,
                              targets.mattes.view.get(), VK_IMAGE_LAYOUT_GENERAL);
    gpu::writeBufferDescriptor(m_ctx, set.set, CW_BIND_RAY_VISIBLE,
                               VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m_visible.buffer.get(),
                               m_visible.size);
    gpu::writeImageDescriptor(m_ctx, set.set, CW_BIND_RAY_MESH_DEPTH,
                              VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, meshDepth.view,
                              meshDepth.layout, m_nearest);
    gpu::writeImageDescriptor(m_ctx, set.set, CW_BIND_RAY_CELLS, storage,
                              m_cells.distance.view.get(), VK_IMAGE_LAYOUT_GENERAL);
    gpu::writeBufferDescriptor(m_ctx, set.set, CW_BIND_RAY_OPERATORS,
                               VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m_operatorUniforms.buffer.get(),
                               m_operatorUniforms.size);
    // Slots without an operator repeat the first one's, or the cells' (unread,
    // but lavapipe binds every descriptor of a set).
    for (std::size_t i = 0; i < CW_RAY_MAX_OPERATORS; ++i) {
        const VkImageView blocks = operators.empty()      ? m_cells.distance.view.get()
                                   : i < operators.size() ? operators[i].blocks
                                                          : operators[0].blocks;
        gpu::writeImageDescriptor(m_ctx, set.set, static_cast<uint32_t>(CW_BIND_RAY_BLOCKS + i),
                                  storage, blocks, VK_IMAGE_LAYOUT_GENERAL);
    }
    return set;
}

namespace {

using gpu::spirv;

// The shader for `operators` operators (0: none, 1: one, more: the loop over
// the slots) in the flavour that `storage` and `lanes` pick
// (shaders/CMakeLists.txt).
gpu::Spirv raySpirv(std::size_t operators, bool storage, bool lanes) {
    if (operators == 0)
        return storage ? (lanes ? spirv(raycast_storage_lanes_comp_spv)
                                : spirv(raycast_storage_comp_spv))
                       : (lanes ? spirv(raycast_lanes_comp_spv) : spirv(raycast_comp_spv));
    if (operators == 1)
        return storage ? (lanes ? spirv(raycast_operator_storage_lanes_comp_spv)
                                : spirv(raycast_operator_storage_comp_spv))
                       : (lanes ? spirv(raycast_operator_lanes_comp_spv)
                                : spirv(raycast_operator_comp_spv));
    return storage ? (lanes ? spirv(raycast_operators_storage_lanes_comp_spv)
                            : spirv(raycast_operators_storage_comp_spv))
                   : (lanes ? spirv(raycast_operators_lanes_comp_spv)
                            : spirv(raycast_operators_comp_spv));
}

} // namespace

VkPipeline Raycaster::pipelineFor(ShaderVariant variant, const std::vector<int>& alignments) {
    variant.storageImages = m_storageImages; // the flavour the layouts were made for
    const auto key = std::make_pair(variant, alignments);
    auto found = m_pipelines.find(key);
    if (found != m_pipelines.end()) return found->second.get();
    auto module = gpu::createShaderModule(
        m_ctx, raySpirv(alignments.size(), variant.storageImages, variant.yieldLanes));
    gpu::PipelineHandle pipeline;
    if (alignments.empty()) {
        const ShaderConstants constants(variant);
        pipeline =
            gpu::createComputePipeline(m_ctx, m_layout.get(), module.get(), constants.info());
    } else {
        // Slot 0's alignment is the slicing shaders' CW_SPEC_ALIGNMENT; then
        // the operator count and slots 1 and 2's alignments.
        ShaderVariant first = variant;
        first.alignment = alignments[0];
        const auto at = [&](std::size_t i) {
            return static_cast<uint32_t>(i < alignments.size() ? alignments[i] : 0);
        };
        const ShaderConstants constants(first,
                                        {static_cast<uint32_t>(alignments.size()), at(1), at(2)});
        pipeline = gpu::createComputePipeline(m_ctx, m_operatorLayout.get(), module.get(),
                                              constants.info());
    }
    return m_pipelines.emplace(key, std::move(pipeline)).first->second.get();
}

void Raycaster::prepareCells(const GpuVolume& volume, const SpanGrid* spans,
                             const VisibleValues& visible, uint64_t occupancySerial, int margin) {
    const std::pair<uint64_t, int> key(occupancySerial, margin);
    if (m_cells.distance.image && m_cells.key == key) return;
    // The shader's Visible block (std430, shared/visible_runs.h).
    const shader::VisibleRuns runs = visible.runs();
    if (!m_visible.buffer)
        m_visible = gpu::createBuffer(m_ctx, sizeof runs, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                      gpu::HostAccess::Write);
    std::memcpy(m_visible.mapped, &runs, sizeof runs);
    m_cells.distance = {}; // freed before its successor is made
    // Without the scan on the host: one occupied cell, the whole box.
    RayCells cells{glm::ivec3(1), {1}, {0}, glm::ivec3(0), glm::ivec3(1)};
    glm::dvec3 cellMm = volume.box.hi - volume.box.lo;
    if (spans) {
        cells = rayCells(*spans, visible);
        cellMm = double(kRayCellVoxels) * volume.spacing;
    }
    const glm::uvec3 n(cells.cells);
    m_cells.distance =
        gpu::createStorageVolume(m_ctx, VK_FORMAT_R8_UINT, {n.x, n.y, n.z}, cells.distance.data(),
                                 cells.distance.size(), VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    m_cells.perTexture = glm::vec4((volume.box.hi - volume.box.lo) / cellMm, double(margin) + 0.5);
    m_cells.bounds = {volume.box.lo + glm::dvec3(cells.lo) * cellMm,
                      glm::min(volume.box.lo + glm::dvec3(cells.hi) * cellMm, volume.box.hi)};
    if (cells.lo == cells.hi) m_cells.bounds = {glm::dvec3(1.0), glm::dvec3(-1.0)}; // rays miss
    m_cells.key = key;
}

void Raycaster::record(VkCommandBuffer cmd, VkDescriptorSet set, const Targets& targets,
                       const CameraMatrices& camera, const ShaderVariant& variant,
                       const std::vector<Operator>& operators, bool operatorTiles) {
    if (operators.size() > CW_RAY_MAX_OPERATORS)
        throw std::logic_error("the ray caster takes at most CW_RAY_MAX_OPERATORS operators");
    for (const gpu::Image* target : {&targets.color, &targets.id, &targets.mattes})
        gpu::transition(cmd, *target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    const VkExtent3D size = targets.color.extent;
    const glm::uvec2 groups((size.width + 7) / 8, (size.height + 7) / 8); // 8x8 invocations each
    // The operators' shader over the tiles their boxes may cover, the
    // volume's over the others (see the shaders' main()).
    const TileRect all{glm::uvec2(0), groups};
    const TileRect opTiles = operators.empty() ? TileRect{}
                             : operatorTiles ? tilesCovering(camera.viewProj, boxCorners(operators),
                                                             glm::uvec2(size.width, size.height))
                                             : all;
    RayPush push{glm::mat4(glm::inverse(camera.viewProj)),
                 glm::vec4(glm::vec3(m_cells.bounds.lo), 0.0f),
                 glm::vec4(glm::vec3(m_cells.bounds.hi), 0.0f),
                 m_cells.perTexture,
                 shader::tileBandStride(groups.y),
                 0u,
                 packTile(opTiles.lo),
                 packTile(opTiles.hi)};
    if (opTiles.lo != all.lo || opTiles.hi != all.hi) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineFor(variant, {}));
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_layout.get(), 0, 1, &set, 0,
                                nullptr);
        vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        vkCmdDispatch(cmd, groups.x, groups.y, 1);
    }
    if (!opTiles.empty()) recordOperators(cmd, set, variant, operators, opTiles, push);
    for (const gpu::Image* target : {&targets.color, &targets.id, &targets.mattes})
        gpu::transition(cmd, *target, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                        VK_ACCESS_2_TRANSFER_READ_BIT);
}

void Raycaster::recordOperators(VkCommandBuffer cmd, VkDescriptorSet set,
                                const ShaderVariant& variant,
                                const std::vector<Operator>& operators, const TileRect& tiles,
                                RayPush push) {
    std::vector<int> alignments;
    // Set 0, then each operator's; unused slots repeat the first operator's
    // (the shader's constants leave them unread, but bound they must be).
    std::vector<VkDescriptorSet> sets{set};
    auto* uniforms = static_cast<shader::OperatorUniforms*>(m_operatorUniforms.mapped);
    for (std::size_t i = 0; i < operators.size(); ++i) {
        alignments.push_back(operators[i].alignment);
        uniforms[i] = *operators[i].uniforms;
    }
    for (std::size_t i = 0; i < CW_RAY_MAX_OPERATORS; ++i)
        sets.push_back(operators[i < operators.size() ? i : 0].set);
    const VkPipelineLayout layout = m_operatorLayout.get();
    const glm::uvec2 groups = tiles.hi - tiles.lo;
    push.bandStride = shader::tileBandStride(groups.y);
    push.tileOffset = packTile(tiles.lo);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineFor(variant, alignments));
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0,
                            static_cast<uint32_t>(sets.size()), sets.data(), 0, nullptr);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, groups.x, groups.y, 1);
}

} // namespace cutaway::render
