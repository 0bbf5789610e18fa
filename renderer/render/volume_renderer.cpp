#include "render/volume_renderer.hpp"

#include "render/frame_image.hpp"
#include "render/mesh_pipeline.hpp"
#include "render/raycast/raycast_pass.hpp"
#include "render/slicing/slicing_pass.hpp"
#include "shared/frame.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace cutaway::render {

VolumeRenderer::VolumeRenderer(const gpu::Context& ctx) : VolumeRenderer(ctx, ctx.tuning()) {}

VolumeRenderer::VolumeRenderer(const gpu::Context& ctx, const gpu::DeviceTuning& tuning)
    : m_ctx(ctx), m_tuning(ctx.supported(tuning)), m_classification(ctx), m_storage(ctx) {
    m_linear = gpu::createLinearSampler(ctx);
    m_nearest = gpu::createNearestSampler(ctx);
    const auto frag = VK_SHADER_STAGE_FRAGMENT_BIT;
    m_frameLayout = gpu::createSetLayout(
        ctx, frameInputBindings(frag, VK_SHADER_STAGE_VERTEX_BIT | frag, m_tuning.storageImages()),
        "slicing frame");
    m_operators = std::make_unique<OperatorStack>(ctx, m_linear.get(), m_tuning.storageImages());
    m_meshes = std::make_unique<MeshPass>(ctx, m_frameLayout.get());
    m_emptySpace = std::make_unique<EmptySpace>(ctx, m_operators->features());
    m_uniforms = gpu::createBuffer(ctx, sizeof(shader::FrameUniforms),
                                   VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::HostAccess::Write);
}

VolumeRenderer::~VolumeRenderer() = default;

RenderPass& VolumeRenderer::passFor(const Scene& scene) {
    const PassResources shared{m_ctx,
                               m_linear.get(),
                               m_nearest.get(),
                               m_frameLayout.get(),
                               m_tuning.storageImages(),
                               *m_operators,
                               *m_emptySpace,
                               *m_meshes};
    if (scene.render.method == RenderMethod::Raycast) {
        if (!m_raycast)
            m_raycast = std::make_unique<RaycastPass>(shared, m_operators->setLayout(), m_tuning);
        return *m_raycast;
    }
    if (!m_slicing) m_slicing = std::make_unique<SlicingPass>(shared, m_operators->setLayout());
    return *m_slicing;
}

ShaderVariant VolumeRenderer::variantFor(const Scene& scene, const GpuVolume& volume) const {
    if (volume.gradientLayout == bake::GradientLayout::Bricked && !m_tuning.storageImages())
        throw std::logic_error("the volume's gradients are bricked for a CPU device's tuning; "
                               "this renderer's shaders cannot read them");
    ShaderVariant v;
    v.storageImages = m_tuning.storageImages();
    v.withAovs = scene.output.anyAov();
    v.labelAovs = scene.output.labelId;
    v.mattes = !scene.output.mattes.empty();
    v.preintegrated = scene.render.classification == Classification::Preintegrated;
    v.byLabel = volume.labels && !scene.labelTransfers.empty();
    v.shading = scene.render.shading.enabled;
    v.lights =
        static_cast<int>(std::min<std::size_t>(scene.lights.directional.size(), CW_MAX_LIGHTS));
    if (m_tuning.storageValues) v.storageFetch = bake::ValueStorageBindings::fetchOf(volume.values);
    v.brickedGradients = volume.gradientLayout == bake::GradientLayout::Bricked;
    v.wholeShininess = wholeShininess(scene.render.shading);
    v.cubic = scene.render.filter == Filter::Cubic;
    v.refine = v.preintegrated ? scene.render.refine : 1;
    v.yieldLanes = m_tuning.yieldLanes;
    v.census = m_census;
    return v;
}

FrameInputs VolumeRenderer::inputsFor(const GpuVolume& volume) {
    FrameInputs in;
    in.uniforms = m_uniforms.buffer.get();
    in.values = &volume.values;
    in.gradients = &volume.gradients;
    in.transfer = &m_classification.transfer();
    in.classes = &m_classification.classes();
    in.linear = m_linear.get();
    in.nearest = m_nearest.get();
    in.storageImages = m_tuning.storageImages();
    if (in.storageImages) {
        const std::array<VkImageView, 2> values = m_storage.views(volume.values);
        in.storage = {values[0], values[1], m_storage.gradientView(volume.gradients)};
    }
    return in;
}

void VolumeRenderer::ensureMeshTargets(glm::uvec2 size, bool withMeshes) {
    if (!withMeshes || m_meshSize != size) {
        m_meshTargets = {};
        m_meshSize = {0, 0};
    }
    if (!withMeshes || m_meshTargets.color.image) return;
    const VkDeviceSize texel = m_ctx.formats().color == VK_FORMAT_R32G32B32A32_SFLOAT ? 16 : 8;
    const VkDeviceSize pixels = VkDeviceSize(size.x) * size.y;
    const auto usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    MeshTargets& t = m_meshTargets;
    t.color = gpu::createImage(m_ctx, VK_IMAGE_TYPE_2D, m_ctx.formats().color, {size.x, size.y, 1},
                               usage);
    t.distance =
        gpu::createImage(m_ctx, VK_IMAGE_TYPE_2D, kMeshDistanceFormat, {size.x, size.y, 1}, usage);
    t.colorReadback = gpu::createBuffer(m_ctx, texel * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                        gpu::HostAccess::Read);
    t.distanceReadback = gpu::createBuffer(m_ctx, 4 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                           gpu::HostAccess::Read);
    m_meshSize = size;
}

Image VolumeRenderer::renderPasses(RenderPass& pass, const Frame& frame,
                                   shader::FrameUniforms& uniforms) {
    // /render/samples passes, each with its samples a further fraction of the
    // spacing along the rays (shared/sampling.h), averaged with the mattes;
    // the first visible samples' channels are the first pass's.
    const int passes = frame.scene.render.samples;
    Image sum;
    for (int k = 0; k < passes; ++k) {
        uniforms.sampling.y = static_cast<float>(k) / static_cast<float>(passes);
        std::memcpy(m_uniforms.mapped, &uniforms, sizeof(uniforms));
        Image image = pass.render(frame, m_stats);
        if (k == 0) {
            sum = std::move(image);
            continue;
        }
        for (std::size_t i = 0; i < sum.rgba.size(); ++i)
            sum.rgba[i] += image.rgba[i];
        for (std::size_t m = 0; m < sum.mattes.size(); ++m)
            for (std::size_t i = 0; i < sum.mattes[m].values.size(); ++i)
                sum.mattes[m].values[i] += image.mattes[m].values[i];
    }
    if (passes > 1) {
        const float scale = 1.0f / static_cast<float>(passes);
        for (float& v : sum.rgba)
            v *= scale;
        for (ImageChannel& matte : sum.mattes)
            for (float& v : matte.values)
                v *= scale;
    }
    return sum;
}

Image VolumeRenderer::render(const Scene& scene, const GpuVolume& volume) {
    const glm::uvec2 size(scene.render.width, scene.render.height);
    m_operators->update(scene.operators, volume);
    const std::optional<Box> meshBounds = m_meshes->prepare(scene, 2.0 * volume.box.radius());
    const FrameGeometry geometry = frameGeometry(scene, volume, *m_operators, meshBounds);
    m_emptySpace->update(scene, volume, geometry.marginVoxels, scene.operators.size());
    m_classification.update(scene, volume, geometry.sliceMm);
    shader::FrameUniforms uniforms =
        frameUniforms(scene, volume, geometry.camera, geometry.sliceMm);
    const bool withMeshes = !m_meshes->empty();
    ensureMeshTargets(size, withMeshes);
    const Frame frame{scene,
                      volume,
                      geometry,
                      size,
                      variantFor(scene, volume),
                      inputsFor(volume),
                      withMeshes ? &m_meshTargets : nullptr};
    m_stats = {0, 0, m_operators->bakes()};
    Image image = renderPasses(passFor(scene), frame, uniforms);
    labelIdsOf(image.labelIds, m_classification.lowestLabel());
    if (withMeshes) {
        const Image meshes = readImage(m_ctx, m_meshTargets.colorReadback, size.x, size.y);
        meshDepthUnder(image, meshes,
                       static_cast<const float*>(m_meshTargets.distanceReadback.mapped));
        compositeMeshes(image, meshes);
    }
    // A census counts samples: no background behind the counts.
    if (!frame.variant.census || scene.render.method != RenderMethod::Raycast)
        compositeUnder(image, scene.render.background);
    return image;
}

} // namespace cutaway::render
