#include "job/render_job.hpp"

#include "core/error.hpp"
#include "job/address_space.hpp"
#include "job/scene_check.hpp"
#include "job/value_checks.hpp"
#include "job/volume_frame.hpp"
#include "operators/operator_geometry.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"
#include "scene/animation.hpp"

#include <algorithm>
#include <cstdio>

namespace cutaway::job {

void applyOverrides(Scene& scene, const RenderOverrides& overrides) {
    if (overrides.outputPattern) scene.output.pattern = *overrides.outputPattern;
    if (overrides.size) {
        scene.render.width = overrides.size->x;
        scene.render.height = overrides.size->y;
    }
    if (overrides.png) scene.output.png = true;
}

FrameRenderer::FrameRenderer(const gpu::Context& ctx) : m_ctx(ctx), m_baker(ctx), m_renderer(ctx) {}

Image FrameRenderer::render(const Scene& given) {
    // Same key, same volume: its texture and gradients are kept.
    FrameVolumeKey key = frameVolumeKey(given);
    if (!m_volume || m_volumeKey != key) {
        m_volume.reset(); // free the old textures before making new ones
        FrameVolume fv = frameVolume(given);
        m_geometry = std::move(fv.geometry);
        // Before the upload and the pipelines: past the limit, the driver fails inside.
        checkAddressSpace(addressSpaceNeed(given, fv.scan.get(), fv.labels.get()));
        const glm::ivec3 dims = fv.scan->dims;
        if (fv.nonFinite > 0 && std::find(m_warnedNonFinite.begin(), m_warnedNonFinite.end(),
                                          key) == m_warnedNonFinite.end()) {
            m_warnedNonFinite.push_back(key);
            m_warnings.push_back(nonFiniteWarning(given, fv.nonFinite, fv.scan->voxelCount()));
        }
        if (fv.labels)
            for (std::string& w : absentLabelWarnings(given, *fv.labels))
                if (m_warnedOnce.insert(w).second) m_warnings.push_back(std::move(w));
        try {
            m_volume = std::make_unique<render::GpuVolume>(render::prepareVolume(
                m_ctx, m_baker, std::move(fv.scan), fv.window, fv.worldLo, std::move(fv.labels)));
        } catch (const ResourceError& e) {
            const VolumeSource& v = given.volume;
            throw ResourceError("the volume " +
                                (v.phantom.empty() ? v.file.string() : "phantom " + v.phantom) +
                                " (" + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                                std::to_string(dims.z) + ") does not fit: " + e.what());
        }
        m_volumeKey = std::move(key);
        ++m_uploads;
    } else {
        checkAddressSpace(addressSpaceNeed(given, m_volume->scan.get(), m_volume->labels.get()));
    }
    // Every frame's transfer functions (animated, or edited under a watch).
    for (const std::string& w : m_values.warnings(given, *m_volume->scan, m_volume->serial))
        if (m_warnedOnce.insert(w).second) m_warnings.push_back(w);
    // Placements given in LPS or RAS, in the volume frame from here on.
    const Scene scene = inVolumeFrame(given, m_geometry);
    warnOfOperatorsOutside(scene);
    Scene live = scene;
    // Attached meshes are placed in the world first: under sequential
    // composition the live operators are a suffix of the scene's.
    for (MeshSpec& mesh : live.meshes) {
        if (!mesh.attach) continue;
        const auto& op = scene.operators[static_cast<std::size_t>(*mesh.attach)];
        mesh.placement = render::operatorFrame(op.localToWorld) * mesh.placement;
        mesh.attach.reset();
    }
    live.operators = liveOperators(scene);
    if (scene.camera.fit == CameraFit::Sequence) live.camera.sequenceBounds = sequenceBounds(given);
    Image image = m_renderer.render(live, *m_volume);
    // The renderer counts the live operators; operator_id names each by its
    // index in the scene, and the live ones are the scene's last.
    const auto first = static_cast<float>(scene.operators.size() - live.operators.size());
    for (float& id : image.operatorIds)
        if (id >= 0.0f) id += first;
    return image;
}

std::array<glm::dvec3, 2> FrameRenderer::sequenceBounds(const Scene& given) {
    // Every frame of one run's scene has the same first frame: the key.
    const Scene first = sceneAtFrame(given, given.animation.firstFrame);
    if (m_sequenceBounds && m_sequenceKey == first.document) return *m_sequenceBounds;
    const operators::WorldBox volumeBox{glm::dmat4(1.0), {m_volume->box.lo, m_volume->box.hi}};
    std::array<glm::dvec3, 2> bounds{m_volume->box.lo, m_volume->box.hi};
    for (int f = given.animation.firstFrame; f <= given.animation.lastFrame; ++f) {
        // As frameGeometry grows the bounds: by each operator that reaches the volume.
        for (const OperatorSpec& op :
             liveOperators(inVolumeFrame(sceneAtFrame(given, f), m_geometry))) {
            if (!operators::intersects(operators::WorldBox{op.localToWorld, {}}, volumeBox))
                continue;
            const operators::WorldBox moved = operators::worldBox(op);
            bounds[0] = glm::min(bounds[0], moved.lo());
            bounds[1] = glm::max(bounds[1], moved.hi());
        }
    }
    m_sequenceKey = first.document;
    m_sequenceBounds = bounds;
    return bounds;
}

void FrameRenderer::warnOfOperatorsOutside(const Scene& scene) {
    // The operator's own box V_T (not where it moves material to): when it
    // misses the volume's box, nothing is cut, moved or kept.
    for (OperatorOutside& o : operatorsOutside(scene, m_volume->box.lo, m_volume->box.hi))
        if (m_warnedOutside.insert(o.index).second) m_warnings.push_back(std::move(o.message));
}

Image renderImage(const gpu::Context& ctx, const Scene& scene) {
    return FrameRenderer(ctx).render(scene);
}

} // namespace cutaway::job
