#include "render/frame.hpp"

#include "core/error.hpp"
#include "gpu/pipeline.hpp"
#include "render/classify/preintegration.hpp"
#include "render/classify/transfer_table.hpp"
#include "render/skipping/occupancy.hpp"
#include "render/slicing/slicer.hpp"
#include "shared/bindings.h"

#include <algorithm>
#include <cmath>

namespace cutaway::render {

std::vector<VkDescriptorSetLayoutBinding> frameInputBindings(VkShaderStageFlags stages,
                                                             VkShaderStageFlags uniformStages,
                                                             bool storageImages) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    std::vector<VkDescriptorSetLayoutBinding> bindings{
        {CW_BIND_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, uniformStages, nullptr},
        {CW_BIND_VALUES, sampled, 1, stages, nullptr},
        {CW_BIND_GRADIENTS, sampled, 1, stages, nullptr},
        {CW_BIND_TRANSFER, sampled, 1, stages, nullptr},
        {CW_BIND_CLASSES, sampled, 1, stages, nullptr}};
    if (storageImages)
        for (uint32_t b : {CW_BIND_VALUES_R8, CW_BIND_VALUES_R16, CW_BIND_GRADIENT_IMAGE})
            bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stages, nullptr});
    return bindings;
}

void writeFrameInputs(const gpu::Context& ctx, VkDescriptorSet set, const FrameInputs& in) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::writeBufferDescriptor(ctx, set, CW_BIND_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                               in.uniforms, sizeof(shader::FrameUniforms));
    gpu::writeImageDescriptor(ctx, set, CW_BIND_VALUES, sampled, in.values->view.get(),
                              in.values->layout, in.linear);
    gpu::writeImageDescriptor(ctx, set, CW_BIND_GRADIENTS, sampled, in.gradients->view.get(),
                              in.gradients->layout, in.linear);
    gpu::writeImageDescriptor(ctx, set, CW_BIND_TRANSFER, sampled, in.transfer->view.get(),
                              in.transfer->layout, in.linear);
    gpu::writeImageDescriptor(ctx, set, CW_BIND_CLASSES, sampled, in.classes->view.get(),
                              in.classes->layout, in.nearest);
    if (!in.storageImages) return;
    const uint32_t bindings[3] = {CW_BIND_VALUES_R8, CW_BIND_VALUES_R16, CW_BIND_GRADIENT_IMAGE};
    for (int i = 0; i < 3; ++i)
        gpu::writeImageDescriptor(ctx, set, bindings[i], VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                  in.storage[i], VK_IMAGE_LAYOUT_GENERAL);
}

Box slicedBounds(const Box& volumeBox, const std::vector<operators::WorldBox>& boxes) {
    // An operator whose own box misses the volume moves nothing and holds nothing.
    const operators::WorldBox volume{glm::dmat4(1.0), {volumeBox.lo, volumeBox.hi}};
    Box bounds = volumeBox;
    for (const operators::WorldBox& box : boxes) {
        if (!operators::intersects(operators::WorldBox{box.localToWorld, {}}, volume)) continue;
        bounds.lo = glm::min(bounds.lo, box.lo());
        bounds.hi = glm::max(bounds.hi, box.hi());
    }
    return bounds;
}

void checkSlicingPlanes(const Scene& scene, const Volume& volume) {
    std::vector<operators::WorldBox> boxes;
    for (const OperatorSpec& spec : scene.operators)
        boxes.push_back(operators::worldBox(spec));
    const glm::dvec3 half = 0.5 * volume.extent();
    const double voxelMm = std::min({volume.spacing.x, volume.spacing.y, volume.spacing.z});
    checkPlaneCount(slicedBounds(Box{-half, half}, boxes), scene.render.sliceSpacing * voxelMm,
                    scene.render.sliceSpacing, voxelMm);
}

FrameGeometry frameGeometry(const Scene& scene, const GpuVolume& volume,
                            const OperatorStack& operators, const std::optional<Box>& meshBounds) {
    std::vector<operators::WorldBox> boxes;
    for (const auto& op : operators.operators())
        boxes.push_back(op->box);
    FrameGeometry g;
    g.bounds = slicedBounds(volume.box, boxes);
    Box inDepth = g.bounds;
    if (meshBounds) {
        inDepth.lo = glm::min(inDepth.lo, meshBounds->lo);
        inDepth.hi = glm::max(inDepth.hi, meshBounds->hi);
    }
    // What a distance of 0 fits (/camera/fit).
    Box fitted = volume.box;
    if (scene.camera.fit == CameraFit::Deformed) fitted = g.bounds;
    if (scene.camera.fit == CameraFit::Sequence) {
        fitted = g.bounds;
        if (const auto& b = scene.camera.sequenceBounds) {
            fitted.lo = glm::min(fitted.lo, (*b)[0]);
            fitted.hi = glm::max(fitted.hi, (*b)[1]);
        }
    }
    inDepth.lo = glm::min(inDepth.lo, fitted.lo);
    inDepth.hi = glm::max(inDepth.hi, fitted.hi);
    if (scene.camera.fit != CameraFit::Volume) {
        // The view aims at the target, which the moved material need not
        // surround: fit a box about the target that holds it all.
        const glm::dvec3 t = scene.camera.target;
        const glm::dvec3 reach = glm::max(glm::abs(fitted.lo - t), glm::abs(fitted.hi - t));
        fitted = Box{t - reach, t + reach};
    }
    g.camera =
        computeCamera(scene.camera, fitted, scene.render.width, scene.render.height, &inDepth);
    g.sliceMm = scene.render.sliceSpacing * volume.smallestSpacing();
    const CameraMatrices& cam = g.camera;
    const double tanX = cam.perspective ? 1.0 / std::abs(cam.proj[0][0]) : 0.0;
    const double tanY = cam.perspective ? 1.0 / std::abs(cam.proj[1][1]) : 0.0;
    g.reachMm = g.sliceMm * std::sqrt(1.0 + tanX * tanX + tanY * tanY) * 1.01;
    g.marginVoxels = slabMargin(g.reachMm / volume.smallestSpacing());
    checkPlaneCount(g.bounds, g.sliceMm, scene.render.sliceSpacing, volume.smallestSpacing());
    return g;
}

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
    u.valueToTf = glm::vec4((n - 1.0f) / n, 0.5f / n,
                            static_cast<float>(opacityUnit(scene, volume.smallestSpacing())), 0.0f);
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
    // A pixel's width in mm is the same everywhere (orthographic) or grows
    // with the depth (perspective); cut_antialias pixels of it are the
    // footprint a cut's coverage is taken over.
    const double pixel = 2.0 / (std::abs(cam.proj[1][1]) * scene.render.height);
    const auto footprint = static_cast<float>(pixel * scene.render.cutAntialias);
    u.termination =
        glm::vec4(static_cast<float>(scene.render.terminationOpacity),
                  cam.perspective ? 0.0f : footprint, cam.perspective ? footprint : 0.0f, 0.0f);
    // The pass's offset is set per pass (VolumeRenderer::renderPasses); the seed
    // wraps at 2^16 so that float keeps it whole.
    const int seed = scene.render.seed.value_or(scene.frame);
    u.sampling =
        glm::vec4(scene.render.jitter ? 1.0f : 0.0f, 0.0f, static_cast<float>(seed % 65536), 0.0f);
    return u;
}

} // namespace cutaway::render
