#include "render/slice_renderer.hpp"

#include "core/error.hpp"
#include "gpu/check.hpp"
#include "operators/operator_geometry.hpp"
#include "render/classification_upload.hpp"
#include "render/occupancy.hpp"
#include "render/preintegration.hpp"
#include "render/ray_cells.hpp"
#include "render/slice_pipeline.hpp"
#include "render/slicer.hpp"
#include "render/transfer_table.hpp"
#include "shared/frame.h"

#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>

namespace cutaway::render {
namespace {

// The shininess as SliceVariant::wholeShininess takes it: the exponent when
// it is a whole number and a highlight is drawn, else 0 (pow).
int wholeShininess(const Shading& shading) {
    const float n = shading.shininess;
    if (!shading.enabled || shading.specular <= 0.0f || n != std::floor(n) || n < 1.0f ||
        n > 512.0f)
        return 0;
    return static_cast<int>(n);
}

shader::FrameUniforms frameUniforms(const Scene& scene, const GpuVolume& volume,
                                    const CameraMatrices& cam, double sliceMm) {
    shader::FrameUniforms u{};
    u.worldToClip = glm::mat4(cam.viewProj);
    u.worldToTexture = glm::mat4(volume.worldToTexture());
    u.eye = glm::vec4(glm::vec3(cam.eye), cam.perspective ? 1.0f : 0.0f);
    u.viewDir = glm::vec4(glm::vec3(cam.forward), static_cast<float>(sliceMm));
    const bool preintegrated = scene.render.classification == Classification::Preintegrated;
    const float n = static_cast<float>(preintegrated ? kPreintegrationSize : kTransferTableSize);
    // Texel centres: value 0 at the centre of entry 0, value 1 at the centre of entry n-1.
    u.valueToTf =
        glm::vec4((n - 1.0f) / n, 0.5f / n, static_cast<float>(volume.smallestSpacing()), 0.0f);
    const Shading& s = scene.render.shading;
    u.material = glm::vec4(scene.lights.ambient, s.diffuse, s.specular, s.shininess);
    u.headlight = glm::vec4(glm::vec3(scene.lights.headlight), 0.0f);
    const auto& lights = scene.lights.directional;
    const std::size_t count = std::min<std::size_t>(lights.size(), CW_MAX_LIGHTS);
    for (std::size_t i = 0; i < count; ++i) {
        u.lightDir[i] = glm::vec4(glm::vec3(-glm::normalize(lights[i].direction)), 0.0f);
        u.lightColor[i] = glm::vec4(lights[i].color * lights[i].intensity, 0.0f);
    }
    const bool byLabel = volume.labels && !scene.labelTransfers.empty();
    u.flags = glm::vec4(static_cast<float>(count), s.enabled ? 1.0f : 0.0f,
                        preintegrated ? 1.0f : 0.0f, byLabel ? 1.0f : 0.0f);
    u.termination =
        glm::vec4(static_cast<float>(scene.render.terminationOpacity), 0.0f, 0.0f, 0.0f);
    return u;
}

// A render-pass attachment cleared at the start: colour to transparent black,
// depth to 1 and stencil to 0.
VkRenderingAttachmentInfo clearedAttachment(VkImageView view, VkImageLayout layout,
                                            VkAttachmentStoreOp store) {
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = view;
    a.imageLayout = layout;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = store;
    if (layout == VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL)
        a.clearValue.depthStencil = {1.0f, 0};
    else
        a.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    return a;
}

// A colour target's pixels from its readback buffer (half or float RGBA).
Image readImage(const gpu::Context& ctx, const gpu::Buffer& readback, int width, int height) {
    Image image(width, height);
    const std::size_t count = image.rgba.size();
    if (ctx.formats().color == VK_FORMAT_R32G32B32A32_SFLOAT) {
        std::memcpy(image.rgba.data(), readback.mapped, count * sizeof(float));
    } else {
        const auto* halves = static_cast<const uint16_t*>(readback.mapped);
        for (std::size_t i = 0; i < count; ++i)
            image.rgba[i] = glm::unpackHalf1x16(halves[i]);
    }
    return image;
}

} // namespace

std::array<VkImageView, 2> SliceRenderer::valueImages(const GpuVolume& volume) const {
    return m_valueBindings.views(volume.values);
}

SliceRenderer::SliceRenderer(const gpu::Context& ctx) : m_ctx(ctx), m_valueBindings(ctx) {
    m_sampler = gpu::createLinearSampler(ctx);
    m_nearest = gpu::createNearestSampler(ctx);
    const auto frag = VK_SHADER_STAGE_FRAGMENT_BIT;
    m_setLayout = gpu::createSetLayout(
        ctx, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT | frag, nullptr},
              {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, frag, nullptr},
              {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, frag, nullptr},
              {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, frag, nullptr},
              {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, frag, nullptr},
              {15, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, frag, nullptr},
              {16, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, frag, nullptr},
              {17, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, frag, nullptr}});
    const bool cpuDevice = ctx.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    setStorageFetch(cpuDevice);
    setYieldLanes(cpuDevice);
    // An operator's set: read by its slicing shader and by the ray caster.
    const auto fragOrCompute = frag | VK_SHADER_STAGE_COMPUTE_BIT;
    m_operatorSetLayout = gpu::createSetLayout(
        ctx, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, fragOrCompute, nullptr},
              {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fragOrCompute, nullptr},
              {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fragOrCompute, nullptr},
              {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fragOrCompute, nullptr},
              {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, fragOrCompute, nullptr}});
    m_layout = gpu::createPipelineLayout(ctx, {m_setLayout.get(), m_operatorSetLayout.get()});
    m_operators = std::make_unique<OperatorStack>(ctx, m_operatorSetLayout.get(), m_sampler.get());
    m_meshes = std::make_unique<MeshPass>(ctx, m_setLayout.get());
    m_saturation = std::make_unique<SaturationPass>(ctx, m_nearest.get());
    m_raycaster = std::make_unique<Raycaster>(ctx, m_sampler.get(), m_nearest.get(),
                                              m_operatorSetLayout.get());
    m_uniforms = gpu::createBuffer(ctx, sizeof(shader::FrameUniforms),
                                   VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::HostAccess::Write);
}

void SliceRenderer::ensureTargets(uint32_t width, uint32_t height, bool withOperatorId,
                                  bool withMeshes, bool slicing) {
    if (m_targetSize != glm::uvec2(width, height)) {
        m_color = {};
        m_depthStencil = {};
        m_readback = {};
        m_operatorId = {};
        m_operatorIdReadback = {};
        m_meshColor = {};
        m_meshReadback = {};
        m_targetSize = {width, height};
    }
    const VkDeviceSize texel = m_ctx.formats().color == VK_FORMAT_R32G32B32A32_SFLOAT ? 16 : 8;
    if (slicing && !m_color.image) {
        m_color =
            gpu::createImage(m_ctx, VK_IMAGE_TYPE_2D, m_ctx.formats().color, {width, height, 1},
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                 VK_IMAGE_USAGE_SAMPLED_BIT);
        m_depthStencil =
            gpu::createImage(m_ctx, VK_IMAGE_TYPE_2D, m_ctx.formats().depthStencil,
                             {width, height, 1}, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                             VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT);
        m_readback = gpu::createBuffer(m_ctx, texel * width * height,
                                       VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::HostAccess::Read);
    }
    if (withMeshes && !m_meshColor.image) {
        m_meshColor =
            gpu::createImage(m_ctx, VK_IMAGE_TYPE_2D, m_ctx.formats().color, {width, height, 1},
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        m_meshReadback = gpu::createBuffer(m_ctx, texel * width * height,
                                           VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::HostAccess::Read);
    }
    if (slicing && withOperatorId && !m_operatorId.image) {
        m_operatorId =
            gpu::createImage(m_ctx, VK_IMAGE_TYPE_2D, kOperatorIdFormat, {width, height, 1},
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        m_operatorIdReadback = gpu::createBuffer(
            m_ctx, 8ull * width * height, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::HostAccess::Read);
    }
}

void SliceRenderer::ensureVertexCapacity(std::size_t bytes) {
    if (m_vertices.buffer && m_vertices.size >= bytes) return;
    m_vertices = gpu::createBuffer(m_ctx, std::max<std::size_t>(bytes * 3 / 2, 4096),
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, gpu::HostAccess::Write);
}

const BrickOccupancy& SliceRenderer::occupancyFor(const Scene& scene, const GpuVolume& volume,
                                                  int marginVoxels) {
    const std::vector<const TransferFunction*> transfers =
        classifyingTransfers(scene, volume.labels != nullptr);
    const bool preintegrated = scene.render.classification == Classification::Preintegrated;
    std::vector<double> key{double(volume.serial), volume.window.lo, volume.window.hi,
                            preintegrated ? 1.0 : 0.0, double(marginVoxels)};
    for (const TransferFunction* tf : transfers) {
        key.push_back(double(tf->points.size()));
        for (const TransferPoint& p : tf->points)
            key.insert(key.end(), {p.value, double(p.alpha)});
    }
    // The spans of values each cell and brick reaches: one pass over the scan
    // per volume, window and margin; a new classification only re-flags them.
    const std::vector<double> spanKey{double(volume.serial), volume.window.lo, volume.window.hi,
                                      double(marginVoxels)};
    if (spanKey != m_spanKey) {
        m_cellSpans.reset();
        m_brickSpans.reset();
        if (volume.scan) {
            m_cellSpans = spanGrid(*volume.scan, volume.window, kRayCellVoxels, 1 + marginVoxels);
            m_brickSpans = brickSpans(*m_cellSpans);
        }
        m_spanKey = spanKey;
    }
    if (key != m_occupiedKey) {
        m_visible.emplace(transfers, volume.window, preintegrated);
        m_occupancy = m_brickSpans
                          ? brickOccupancy(*m_brickSpans, volume.box, volume.spacing, *m_visible)
                          : fullOccupancy(volume.box);
        m_occupied = m_occupancy.boxes();
        m_occupiedKey = std::move(key);
        ++m_occupancySerial;
    }
    return m_occupancy;
}

SliceRenderer::Regions& SliceRenderer::regionsFor(std::size_t index, const GpuOperator& op,
                                                  double reachMm) {
    // What the regions depend on: the occupancy, the feature field and the
    // mask's threshold, the map and where it lies.
    const Alignment& alignment = op.spec.alignment;
    std::vector<double> key{double(m_occupancySerial), reachMm, double(op.fieldId),
                            double(alignmentCode(alignment.mode)), alignment.depth};
    const auto add = [&](const float* v, std::size_t n) { key.insert(key.end(), v, v + n); };
    add(&op.spec.params.a.x, sizeof op.spec.params / sizeof(float));
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            key.push_back(op.box.localToWorld[c][r]);
    for (int a = 0; a < 3; ++a)
        key.insert(key.end(),
                   {op.box.local.lo[a], op.box.local.hi[a], double(op.spec.resolution[a])});
    if (m_regions.size() <= index) m_regions.resize(index + 1);
    Regions& r = m_regions[index];
    if (r.key != key) r = Regions{std::move(key), std::nullopt, {}};
    return r;
}

const std::vector<operators::LocalBox>&
SliceRenderer::boxesFor(std::size_t index, const GpuOperator& op, double reachMm) {
    Regions& r = regionsFor(index, op, reachMm);
    if (!r.boxes) r.boxes = operatorRegions(op.spec, op.box, m_occupancy, reachMm); // feature-blind
    return *r.boxes;
}

const CaseOccupancy& SliceRenderer::casesFor(const GpuOperator& op) {
    const Alignment& a = op.spec.alignment;
    const bool surface = a.mode == AlignmentMode::Surface;
    const double threshold = surface ? a.depth : 0.5;
    std::vector<double> key{double(m_occupancySerial), double(op.fieldId), threshold,
                            double(alignmentCode(a.mode))};
    const auto found = m_cases.find(key);
    if (found != m_cases.end()) return found->second;
    // Those of an older occupancy are stale; a sequence that changes the
    // fields or thresholds as it goes keeps no more than a few.
    std::erase_if(m_cases, [&](const auto& c) { return c.first[0] != key[0]; });
    if (m_cases.size() >= 2 * CW_RAY_MAX_OPERATORS) m_cases.clear();
    if (a.mode == AlignmentMode::Axis)
        return m_cases.emplace(key, CaseOccupancy::movedOnly(m_occupancy)).first->second;
    const bake::FieldRanges* ranges =
        m_cellSpans ? m_operators->features().rangesOf(op.fieldId, m_cellSpans->cellVoxels)
                    : nullptr;
    return m_cases
        .emplace(key, CaseOccupancy::withFeature(m_occupancy, m_cellSpans ? &*m_cellSpans : nullptr,
                                                 m_visible ? &*m_visible : nullptr, ranges,
                                                 threshold, !surface))
        .first->second;
}

VkPipeline SliceRenderer::pipelineFor(const SliceVariant& variant) {
    auto found = m_pipelines.find(variant);
    if (found == m_pipelines.end())
        found =
            m_pipelines.emplace(variant, createSlicePipeline(m_ctx, m_layout.get(), variant)).first;
    return found->second.get();
}

void SliceRenderer::recordSlices(VkCommandBuffer cmd, const SliceSet& slices,
                                 VkDescriptorSet frameSet, SliceVariant frame, std::size_t begin,
                                 std::size_t end) {
    frame.proxy = SliceProxy::Background;
    const VkPipeline background = pipelineFor(frame);
    std::vector<VkPipeline> operatorPipelines; // by the operator's alignment
    for (const auto& op : m_operators->operators()) {
        SliceVariant v = frame;
        v.proxy = SliceProxy::Operator;
        v.alignment = alignmentCode(op->spec.alignment.mode);
        operatorPipelines.push_back(pipelineFor(v));
    }
    VkDeviceSize offset = 0;
    VkBuffer vb = m_vertices.buffer.get();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_layout.get(), 0, 1, &frameSet,
                            0, nullptr);
    const auto& ops = m_operators->operators();
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
    frame.proxy = SliceProxy::OperatorStencil;
    const VkPipeline stencil = pipelineFor(frame);
    for (std::size_t k = begin; k < end; ++k) {
        // Stencil references cycle through 1..255; before a value comes back,
        // clear the stencil so an old slice's mark cannot hide the background.
        if (k > 0 && k % 255 == 0) {
            VkClearAttachment clear{VK_IMAGE_ASPECT_STENCIL_BIT, 0, {}};
            clear.clearValue.depthStencil = {1.0f, 0};
            VkClearRect rect{{{0, 0}, {m_color.extent.width, m_color.extent.height}}, 0, 1};
            vkCmdClearAttachments(cmd, 1, &clear, 1, &rect);
        }
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

Image SliceRenderer::render(const Scene& scene, const GpuVolume& volume) {
    const int width = scene.render.width, height = scene.render.height;
    m_operators->update(scene.operators, volume);
    if (m_regions.size() > scene.operators.size()) m_regions.resize(scene.operators.size());
    // What the frame holds: the volume, and the deformed boxes of the
    // operators that reach it (a flap may leave the volume's box; an operator
    // whose own box misses the volume moves nothing and holds nothing). The
    // camera frames the volume alone, so that an operator moving through a
    // sequence does not move the camera; its depth range covers the rest.
    const operators::WorldBox volumeBox{glm::dmat4(1.0), {volume.box.lo, volume.box.hi}};
    Box bounds = volume.box;
    for (const auto& op : m_operators->operators()) {
        if (!operators::intersects(operators::WorldBox{op->spec.localToWorld, {}}, volumeBox))
            continue;
        bounds.lo = glm::min(bounds.lo, op->box.lo());
        bounds.hi = glm::max(bounds.hi, op->box.hi());
    }
    const std::optional<Box> meshBounds = m_meshes->prepare(scene, 2.0 * volume.box.radius());
    Box inDepth = bounds;
    if (meshBounds) {
        inDepth.lo = glm::min(inDepth.lo, meshBounds->lo);
        inDepth.hi = glm::max(inDepth.hi, meshBounds->hi);
    }
    const CameraMatrices cam = computeCamera(scene.camera, volume.box, width, height, &inDepth);
    const double sliceMm = scene.render.sliceSpacing * volume.smallestSpacing();
    // Proxies: each operator's deformed box, then the volume (the background).
    // An operator's box is a stencil-only proxy, its shader runs on its regions.
    // How far along a ray a fragment's slab reaches: the slice spacing,
    // longer by the obliquity of the frame's most oblique ray.
    const double tanX = cam.perspective ? 1.0 / std::abs(cam.proj[0][0]) : 0.0;
    const double tanY = cam.perspective ? 1.0 / std::abs(cam.proj[1][1]) : 0.0;
    const double reachMm = sliceMm * std::sqrt(1.0 + tanX * tanX + tanY * tanY) * 1.01;
    const int margin = slabMargin(reachMm / volume.smallestSpacing()); // for empty space
    occupancyFor(scene, volume, margin);
    const bool raycast = scene.render.method == RenderMethod::Raycast;
    std::vector<Proxy> proxies; // none for the ray caster
    m_roles.clear();
    const auto& ops = m_operators->operators();
    for (std::size_t i = 0; i < (raycast ? 0 : ops.size()); ++i) {
        const GpuOperator& op = *ops[i];
        const int index = static_cast<int>(i);
        proxies.push_back(orientedBoxProxy(op.box.localToWorld, op.box.local.lo, op.box.local.hi));
        if (!m_operatorSkipping) {
            m_roles.push_back({index, false});
            continue;
        }
        const std::vector<operators::LocalBox>& regions = boxesFor(i, op, reachMm);
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
    // The volume's proxy: its occupied bricks (empty-space skipping).
    for (const Box& box : raycast ? std::vector<Box>{} : m_occupied) {
        proxies.push_back(boxProxy(box));
        m_roles.push_back({});
    }
    checkPlaneCount(bounds, sliceMm, scene.render.sliceSpacing, volume.smallestSpacing());
    const double minDepth = cam.perspective ? cam.nearPlane : -1e30;
    const SliceSet slices =
        raycast ? SliceSet{} : buildSlices(proxies, cam.eye, cam.forward, sliceMm, minDepth);
    m_stats = {slices.sliceCount, slices.triangles.size(), m_operators->bakes()};

    const std::size_t vertexBytes = slices.triangles.size() * sizeof(glm::vec3);
    ensureVertexCapacity(vertexBytes);
    if (vertexBytes) std::memcpy(m_vertices.mapped, slices.triangles.data(), vertexBytes);
    const shader::FrameUniforms uniforms = frameUniforms(scene, volume, cam, sliceMm);
    std::memcpy(m_uniforms.mapped, &uniforms, sizeof(uniforms));
    const bool withId = scene.output.operatorId;
    const bool withMeshes = !m_meshes->empty();
    ensureTargets(static_cast<uint32_t>(width), static_cast<uint32_t>(height), withId, withMeshes,
                  !raycast);
    // Everything the classification table depends on; a turntable keeps it.
    std::vector<double> transferKey{
        double(scene.render.classification == Classification::Preintegrated), volume.window.lo,
        volume.window.hi, sliceMm, volume.smallestSpacing()};
    const auto addPoints = [&](const TransferFunction& tf) {
        transferKey.push_back(double(tf.points.size()));
        for (const TransferPoint& p : tf.points)
            transferKey.insert(transferKey.end(),
                               {p.value, p.color.x, p.color.y, p.color.z, double(p.alpha)});
    };
    addPoints(scene.transfer);
    // Label layers: which labels take which function, and the label volume.
    std::vector<double> classKey{double(volume.serial)};
    if (volume.labels) {
        for (const LabelTransfer& t : scene.labelTransfers) {
            addPoints(t.transfer);
            classKey.push_back(-1.0);
            classKey.insert(classKey.end(), t.ids.begin(), t.ids.end());
        }
    }
    if (!m_transfer.image || transferKey != m_transferKey) {
        m_transfer = uploadTransfer(m_ctx, scene, volume, sliceMm);
        m_transferKey = std::move(transferKey);
    }
    if (!m_classes.image || classKey != m_classesKey) {
        m_classes = uploadClasses(m_ctx, scene, volume);
        m_classesKey = std::move(classKey);
    }
    const gpu::Image& transfer = m_transfer;

    gpu::DescriptorSet set =
        gpu::allocateDescriptorSet(m_ctx, m_setLayout.get(),
                                   {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                    {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 3}});
    gpu::writeBufferDescriptor(m_ctx, set.set, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                               m_uniforms.buffer.get(), sizeof(uniforms));
    const auto ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::writeImageDescriptor(m_ctx, set.set, 1, sampled, volume.values.view.get(),
                              bake::kValuesLayout, m_sampler.get());
    const std::array<VkImageView, 2> valueViews = valueImages(volume);
    for (uint32_t i = 0; i < 2; ++i)
        gpu::writeImageDescriptor(m_ctx, set.set, 15 + i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                  valueViews[i], VK_IMAGE_LAYOUT_GENERAL);
    gpu::writeImageDescriptor(m_ctx, set.set, 2, sampled, volume.gradients.view.get(),
                              bake::kGradientsLayout, m_sampler.get());
    gpu::writeImageDescriptor(m_ctx, set.set, 17, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                              volume.gradients.view.get(), bake::kGradientsLayout);
    gpu::writeImageDescriptor(m_ctx, set.set, 3, sampled, transfer.view.get(), ro, m_sampler.get());
    gpu::writeImageDescriptor(m_ctx, set.set, 4, sampled, m_classes.view.get(), ro,
                              m_nearest.get());

    std::vector<const gpu::Image*> targets{&m_color};
    std::vector<const gpu::Buffer*> readbacks{&m_readback};
    if (withId) {
        targets.push_back(&m_operatorId);
        readbacks.push_back(&m_operatorIdReadback);
    }
    const std::size_t volumeTargets = targets.size(); // the mesh target is not in the volume pass
    if (withMeshes) {
        targets.push_back(&m_meshColor);
        readbacks.push_back(&m_meshReadback);
    }
    SliceVariant variant; // what this frame fixes in the shaders
    variant.withOperatorId = withId;
    variant.preintegrated = scene.render.classification == Classification::Preintegrated;
    variant.byLabel = volume.labels && !scene.labelTransfers.empty();
    variant.shading = scene.render.shading.enabled;
    variant.lights =
        static_cast<int>(std::min<std::size_t>(scene.lights.directional.size(), CW_MAX_LIGHTS));
    if (m_storageFetch) variant.storageFetch = bake::ValueStorageBindings::fetchOf(volume.values);
    variant.brickedGradients = volume.gradientLayout == bake::GradientLayout::Bricked;
    variant.wholeShininess = wholeShininess(scene.render.shading);
    if (raycast) {
        variant.census = m_census;
        variant.yieldLanes = m_yieldLanes;
        Image image = renderRaycast(cam, volume, transfer, variant, margin, reachMm, set.set);
        if (!m_census) compositeUnder(image, scene.render.background);
        return image;
    }
    const gpu::DescriptorSet saturationSet = m_saturation->bind(m_color);
    m_ctx.submitAndWait([&](VkCommandBuffer cmd) {
        for (const gpu::Image* target : targets)
            gpu::transition(cmd, *target, VK_IMAGE_LAYOUT_UNDEFINED,
                            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
                            VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
        gpu::transition(cmd, m_depthStencil, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
                        VK_ACCESS_2_NONE,
                        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                            VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);

        if (withMeshes) m_meshes->recordPass(cmd, set.set, m_meshColor, m_depthStencil);
        VkRenderingAttachmentInfo colors[2];
        for (std::size_t t = 0; t < volumeTargets; ++t)
            colors[t] =
                clearedAttachment(targets[t]->view.get(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                  VK_ATTACHMENT_STORE_OP_STORE);
        VkRenderingAttachmentInfo ds = clearedAttachment(
            m_depthStencil.view.get(), VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
            VK_ATTACHMENT_STORE_OP_STORE);
        VkRenderingAttachmentInfo depthAttachment = ds; // the meshes' depth, when there are any
        if (withMeshes) depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{0, 0}, {m_color.extent.width, m_color.extent.height}};
        info.layerCount = 1;
        info.colorAttachmentCount = static_cast<uint32_t>(volumeTargets);
        info.pColorAttachments = colors;
        info.pDepthAttachment = &depthAttachment;
        info.pStencilAttachment = &ds;
        const VkViewport viewport{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height),
                                  0.0f, 1.0f};
        // Chunks of slices; between two, the saturation pass marks opaque
        // pixels so the slices behind them are not shaded (early termination).
        const std::size_t count = slices.slices.size();
        for (std::size_t begin = 0; begin < std::max<std::size_t>(count, 1);
             begin += kSlicesPerChunk) {
            if (begin > 0) {
                m_saturation->record(cmd, saturationSet.set, m_color, m_depthStencil,
                                     uniforms.termination.x);
                for (std::size_t t = 0; t < volumeTargets; ++t)
                    colors[t].loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
                depthAttachment.loadOp = ds.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
            }
            vkCmdBeginRendering(cmd, &info);
            vkCmdSetViewport(cmd, 0, 1, &viewport);
            vkCmdSetScissor(cmd, 0, 1, &info.renderArea);
            if (count)
                recordSlices(cmd, slices, set.set, variant, begin,
                             std::min(count, begin + kSlicesPerChunk));
            vkCmdEndRendering(cmd);
        }

        for (std::size_t t = 0; t < targets.size(); ++t) {
            gpu::transition(cmd, *targets[t], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                            VK_ACCESS_2_TRANSFER_READ_BIT);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = targets[t]->extent;
            vkCmdCopyImageToBuffer(cmd, targets[t]->image.get(),
                                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readbacks[t]->buffer.get(),
                                   1, &region);
        }
        gpu::barrierTransferToHost(cmd);
    });

    Image image = readImage(m_ctx, m_readback, width, height);
    const std::size_t pixels = image.rgba.size();
    if (withId) { // codes: 0 nothing visible, 2 the untouched volume, 3 + i operator i
        const auto* halves = static_cast<const uint16_t*>(m_operatorIdReadback.mapped);
        image.operatorIds.resize(pixels / 4);
        for (std::size_t p = 0; p < image.operatorIds.size(); ++p) {
            const float code = glm::unpackHalf1x16(halves[4 * p]);
            const float covered = glm::unpackHalf1x16(halves[4 * p + 3]);
            image.operatorIds[p] = operatorIdOf(code, covered > 0.5f);
        }
    }
    if (withMeshes) compositeMeshes(image);
    compositeUnder(image, scene.render.background);
    return image;
}

// The operator_id channel's value for a pixel whose first visible sample
// came from the proxy with this code (see CW_ID_BACKGROUND in
// shaders/glsl/sample_common.h): -2 nothing visible, -1 the untouched volume,
// i operator i.
float SliceRenderer::operatorIdOf(float code, bool covered) {
    return covered ? std::round(code) - 3.0f : -2.0f;
}

void SliceRenderer::compositeMeshes(Image& image) const {
    // The meshes are opaque and lie behind the volume in front of them.
    const Image meshes = readImage(m_ctx, m_meshReadback, image.width, image.height);
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
        const float t = 1.0f - image.rgba[i + 3];
        for (int c = 0; c < 4; ++c)
            image.rgba[i + c] += t * meshes.rgba[i + c];
    }
}

void SliceRenderer::compositeUnder(Image& image, glm::vec4 background) {
    // The background lies behind everything: composite it "under" the volume.
    const glm::vec4 premultiplied(glm::vec3(background) * background.w, background.w);
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
        const float t = 1.0f - image.rgba[i + 3];
        for (int c = 0; c < 4; ++c)
            image.rgba[i + c] += t * premultiplied[c];
    }
}

} // namespace cutaway::render
