#include "render/gpu_operators.hpp"

#include "render/skipping/operator_regions.hpp"
#include "shared/bindings.h"
#include "shared/feature.h"
#include "shared/operator_frame.h"

#include <cstring>

namespace cutaway::render {

int alignmentCode(AlignmentMode mode) {
    return mode == AlignmentMode::Surface   ? CW_ALIGN_SURFACE
           : mode == AlignmentMode::Segment ? CW_ALIGN_SEGMENT
                                            : CW_ALIGN_AXIS;
}
namespace {

bool sameMap(const OperatorSpec& a, const OperatorSpec& b) {
    return std::memcmp(&a.params, &b.params, sizeof a.params) == 0 && a.resolution == b.resolution;
}

shader::OperatorUniforms uniformsOf(const OperatorSpec& spec, const operators::WorldBox& box,
                                    std::size_t index, const GpuVolume& volume,
                                    const gpu::Image& region, bake::VoxelRegion voxels) {
    shader::OperatorUniforms u{};
    u.localToWorld = glm::mat4(spec.localToWorld);
    u.worldToLocal = glm::mat4(glm::inverse(spec.localToWorld));
    const glm::dvec3 texel = (box.local.hi - box.local.lo) / glm::dvec3(spec.resolution);
    u.mapLo = glm::vec4(glm::vec3(box.local.lo),
                        static_cast<float>(operators::cutMarginCap(spec, box.local)));
    u.mapHi = glm::vec4(glm::vec3(box.local.hi),
                        static_cast<float>(std::min({texel.x, texel.y, texel.z})));
    // D of Eq. 7 from millimetres to the units of w: the mean scale of the
    // frame; the peeler's w is in units of its half z (operators.h).
    const glm::dmat3 a(spec.localToWorld);
    const double scale = spec.type == OperatorType::Peeler
                             ? glm::length(a[2])
                             : (glm::length(a[0]) + glm::length(a[1]) + glm::length(a[2])) / 3.0;
    u.band = glm::vec4(static_cast<float>(spec.normalBand / scale), static_cast<float>(index + 3),
                       0.0f, static_cast<float>(operators::cutSlope(spec))); // id: slice_common.h
    if (spec.cutFace) { // its layer in the same units as D
        u.band.z = static_cast<float>(spec.cutFace->depth / scale);
        u.cutFace = glm::vec4(spec.cutFace->color, static_cast<float>(spec.cutFace->mix));
    }
    const Alignment& al = spec.alignment;
    const float mode = static_cast<float>(alignmentCode(al.mode));
    u.align = glm::vec4(mode, static_cast<float>(al.depth), static_cast<float>(al.band),
                        static_cast<float>(al.band));
    // The feature field is on the volume's grid (a 1^3 texture for axis alignment).
    u.featureScale = glm::vec4(glm::vec3(0.5 / volume.spacing), 0.0f);
    // Segment alignment's texture covers a region: voxel lo + j of the grid
    // is its texel j.
    u.featureTc = glm::vec4(1.0f);
    u.featureTc0 = glm::vec4(0.0f);
    if (region.image) {
        const glm::dvec3 size(voxels.size);
        u.featureTc = glm::vec4(glm::vec3(glm::dvec3(volume.dims) / size), 0.0f);
        u.featureTc0 = glm::vec4(glm::vec3(-glm::dvec3(voxels.lo) / size), 0.0f);
    }
    u.blocks = glm::vec4(glm::vec3(spec.resolution) / float(kOperatorBlockTexels), 0.0f);
    return u;
}

} // namespace

OperatorStack::OperatorStack(const gpu::Context& ctx, VkSampler sampler, bool storageImages)
    : m_ctx(ctx), m_storageImages(storageImages), m_sampler(sampler), m_baker(ctx),
      m_regionBaker(ctx), m_features(ctx, storageImages) {
    // Read by the operator's slicing shader and by the ray caster.
    const auto stages = VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    std::vector<VkDescriptorSetLayoutBinding> bindings{
        {CW_BIND_OP_UNIFORMS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, stages, nullptr},
        {CW_BIND_OP_MAP, sampled, 1, stages, nullptr},
        {CW_BIND_OP_FEATURE, sampled, 1, stages, nullptr},
        {CW_BIND_OP_DERIVATIVES, sampled, 1, stages, nullptr}};
    if (storageImages)
        bindings.push_back(
            {CW_BIND_OP_FEATURE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stages, nullptr});
    m_setLayout = gpu::createSetLayout(ctx, bindings, "operator");
}

void OperatorStack::update(const std::vector<OperatorSpec>& specs, const GpuVolume& volume) {
    // Deformed bounds depend only on the parameters: keep them while the map is kept.
    std::vector<operators::WorldBox> boxes;
    for (std::size_t i = 0; i < specs.size(); ++i) {
        const bool kept =
            i < m_operators.size() && m_operators[i] && sameMap(m_operators[i]->spec, specs[i]);
        boxes.push_back({specs[i].localToWorld,
                         kept ? m_operators[i]->box.local
                              : operators::deformedBounds(specs[i].params, specs[i].resolution)});
    }
    operators::checkNoOverlap(specs, boxes); // before anything changes
    m_operators.resize(specs.size());
    m_features.keepOnly(specs, volume);
    for (std::size_t i = 0; i < specs.size(); ++i) {
        auto& op = m_operators[i];
        const OperatorSpec& spec = specs[i];
        const bool rebake = !op || !sameMap(op->spec, spec);
        if (!op) {
            op = std::make_unique<GpuOperator>();
            op->uniforms =
                gpu::createBuffer(m_ctx, sizeof(shader::OperatorUniforms),
                                  VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::HostAccess::Write);
            op->set = gpu::allocateDescriptorSet(
                m_ctx, m_setLayout.get(),
                {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                 {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 3},
                 {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, m_storageImages ? 1u : 0u}});
            gpu::writeBufferDescriptor(m_ctx, op->set.set, CW_BIND_OP_UNIFORMS,
                                       VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, op->uniforms.buffer.get(),
                                       sizeof(shader::OperatorUniforms));
        }
        op->box = boxes[i];
        if (rebake) {
            const operators::LocalBox& local = op->box.local;
            op->map = {}; // freed before their successors are made
            op->derivatives = {};
            bake::BakedMap baked =
                m_baker.bake(operators::sampledParams(spec.params, local, spec.resolution),
                             glm::vec3(local.lo), glm::vec3(local.hi), spec.resolution);
            op->map = std::move(baked.map);
            op->derivatives = std::move(baked.derivatives);
            gpu::writeImageDescriptor(m_ctx, op->set.set, CW_BIND_OP_MAP,
                                      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, op->map.view.get(),
                                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, m_sampler);
            gpu::writeImageDescriptor(m_ctx, op->set.set, CW_BIND_OP_DERIVATIVES,
                                      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                      op->derivatives.view.get(),
                                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, m_sampler);
            ++m_bakes;
        }
        std::uint64_t fieldId = 0;
        const gpu::Image& field = m_features.fieldFor(spec, volume, &fieldId);
        op->fieldId = fieldId;
        const gpu::Image* feature = &field;
        VkImageLayout featureLayout = bake::kFeatureLayout;
        if (spec.alignment.mode == AlignmentMode::Segment) {
            // The region the map reads: its deformed box holds p' and p0.
            const bake::VoxelRegion voxels = bake::regionCovering(
                volume.dims, volume.spacing, volume.box.lo, op->box.lo(), op->box.hi());
            if (!op->region.image || op->regionField != fieldId || !(op->regionVoxels == voxels)) {
                op->region = {}; // freed before its successor is made
                op->region = m_regionBaker.bake(volume.values, field, voxels);
                op->regionField = fieldId;
                op->regionVoxels = voxels;
            }
            feature = &op->region;
            featureLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        } else {
            op->region = {};
        }
        gpu::writeImageDescriptor(m_ctx, op->set.set, CW_BIND_OP_FEATURE,
                                  VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, feature->view.get(),
                                  featureLayout, m_sampler);
        // The field on the volume's grid again, for the shaders that load its
        // texels (surface alignment on CPU devices; operator_sample.h).
        if (m_storageImages)
            gpu::writeImageDescriptor(m_ctx, op->set.set, CW_BIND_OP_FEATURE_IMAGE,
                                      VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, field.view.get(),
                                      bake::kFeatureLayout);
        op->spec = spec;
        const shader::OperatorUniforms u =
            uniformsOf(spec, op->box, i, volume, op->region, op->regionVoxels);
        std::memcpy(op->uniforms.mapped, &u, sizeof u);
    }
}

} // namespace cutaway::render
