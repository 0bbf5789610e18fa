#include "job/scene_check.hpp"

#include "core/error.hpp"
#include "job/render_job.hpp"
#include "job/value_checks.hpp"
#include "job/volume_frame.hpp"
#include "mesh/mesh.hpp"
#include "operators/operator_geometry.hpp"
#include "render/classify/label_classes.hpp"
#include "render/frame.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <set>

namespace cutaway::job {

std::vector<OperatorOutside> operatorsOutside(const Scene& scene, glm::dvec3 lo, glm::dvec3 hi) {
    const operators::WorldBox volume{glm::dmat4(1.0), {lo, hi}};
    std::vector<OperatorOutside> outside;
    for (std::size_t i = 0; i < scene.operators.size(); ++i) {
        const OperatorSpec& op = scene.operators[i];
        if (operators::intersects(operators::WorldBox{op.localToWorld, {}}, volume)) continue;
        outside.push_back(
            {i, "/operators/" + std::to_string(i) + ": \"" + op.name +
                    "\" lies outside the volume, so it changes nothing; "
                    "\"volume\" placements are in mm with the volume's centre at the origin"});
    }
    return outside;
}

namespace {

// What the volume and label files of a frame depend on: frameVolumeKey
// without the operators, which change nothing that is read. The window
// stays: non-finite voxels take the value of empty space, which it sets.
FrameVolumeKey filesKey(const Scene& scene) {
    Scene probe;
    probe.volume = scene.volume;
    probe.labels = scene.labels;
    return frameVolumeKey(probe);
}

// Refuses a segment-aligned operator whose segment holds no voxel of the
// scan, as its bake would (render/classify/label_classes.hpp), a slab at a time.
void checkSegmentNotEmpty(const OperatorSpec& op, const Volume& scan, const Volume* labels) {
    render::SegmentIndicator segment(op, scan, labels);
    const std::size_t total = scan.voxelCount();
    std::vector<std::uint8_t> slab(std::min<std::size_t>(total, std::size_t(1) << 20));
    for (std::size_t first = 0; first < total; first += slab.size())
        segment.write(first, std::min(slab.size(), total - first), slab.data());
    segment.checkNotEmpty();
}

} // namespace

std::size_t SceneFileCheck::filesOf(const Scene& scene) {
    FrameVolumeKey key = filesKey(scene);
    auto it = std::find_if(m_files.begin(), m_files.end(),
                           [&](const Files& files) { return files.key == key; });
    if (it == m_files.end()) {
        Files files;
        files.key = std::move(key);
        try {
            // Sequential composition resamples the scan and drops its labels
            // (frameVolume): they are not read for such a frame.
            files.scan = std::make_shared<const Volume>(loadSceneVolume(scene, &files.nonFinite));
            if (!sequential(scene)) files.labels = loadSceneLabels(scene, files.scan);
        } catch (const InputError& e) {
            files.error = e.what(); // read once, reported for every frame that names them
        }
        m_files.push_back(std::move(files));
        it = m_files.end() - 1;
    }
    if (!it->error.empty()) throw InputError(it->error);
    return static_cast<std::size_t>(it - m_files.begin());
}

void SceneFileCheck::frame(const Scene& given) {
    const std::size_t filesIndex = filesOf(given);
    const Files& files = m_files[filesIndex];
    const Scene scene = inVolumeFrame(given, *files.scan); // LPS and RAS placed as a render does
    render::checkSlicingPlanes(scene, *files.scan);
    if (!sequential(scene)) {
        // What each frame's render refuses before it draws: overlapping
        // operators, a segment without voxels (its scan and labels as read).
        operators::checkNoOverlap(scene.operators);
        for (std::size_t i = 0; i < scene.operators.size(); ++i) {
            const OperatorSpec& op = scene.operators[i];
            if (op.alignment.mode != AlignmentMode::Segment) continue;
            // The message names the operator: one key per operator.
            const SegmentKey key{filesIndex, op.alignment.labels, op.alignment.range, i, op.name};
            if (!m_segments.contains(key)) {
                std::string error;
                try {
                    checkSegmentNotEmpty(op, *files.scan, files.labels.get());
                } catch (const InputError& e) {
                    error = e.what();
                }
                m_segments.emplace(key, error);
            }
            if (const std::string& error = m_segments.at(key); !error.empty())
                throw InputError(error);
        }
    }
    for (const MeshSpec& mesh : scene.meshes)
        if (m_meshesRead.insert(mesh.file.string()).second) mesh::loadGltf(mesh.file);
    if (files.nonFinite > 0 && m_warnedFiles.insert(filesIndex).second)
        m_warnings.push_back(nonFiniteWarning(scene, files.nonFinite, files.scan->voxelCount()));
    for (const std::string& w : m_values.warnings(scene, *files.scan, filesIndex))
        if (m_warnedOnce.insert(w).second) m_warnings.push_back(w);
    for (const std::string& n : m_values.notes(scene, *files.scan, filesIndex))
        if (m_noted.insert(n).second) m_notes.push_back(n);
    if (files.labels)
        for (std::string& w : absentLabelWarnings(scene, *files.labels))
            if (m_warnedOnce.insert(w).second) m_warnings.push_back(std::move(w));
    const glm::dvec3 extent = files.scan->extent();
    for (OperatorOutside& o : operatorsOutside(scene, -0.5 * extent, 0.5 * extent))
        if (m_warned.insert(o.index).second) m_warnings.push_back(std::move(o.message));
}

} // namespace cutaway::job
