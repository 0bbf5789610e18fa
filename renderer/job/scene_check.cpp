#include "job/scene_check.hpp"

#include "core/error.hpp"
#include "job/render_job.hpp"
#include "mesh/mesh.hpp"
#include "operators/operator_geometry.hpp"
#include "render/classify/label_classes.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace cutaway::job {

std::vector<OperatorOutside> operatorsOutside(const Scene& scene, glm::dvec3 lo, glm::dvec3 hi) {
    const operators::WorldBox volume{glm::dmat4(1.0), {lo, hi}};
    std::vector<OperatorOutside> outside;
    for (std::size_t i = 0; i < scene.operators.size(); ++i) {
        const OperatorSpec& op = scene.operators[i];
        if (operators::intersects(operators::WorldBox{op.localToWorld, {}}, volume)) continue;
        outside.push_back({i, "/operators/" + std::to_string(i) + ": \"" + op.name +
                                  "\" lies outside the volume, so it changes nothing; "
                                  "placements are in mm with the volume's centre at the origin"});
    }
    return outside;
}

namespace {

// What the volume and label files of a frame depend on: frameVolumeKey
// without the window and the operators, which change nothing that is read.
std::string filesKey(const Scene& scene) {
    Scene probe;
    probe.volume = scene.volume;
    probe.volume.window.reset();
    probe.labels = scene.labels;
    return frameVolumeKey(probe);
}

// What a segment-aligned operator's indicator depends on beyond the files.
std::string segmentKey(const Alignment& a) {
    std::ostringstream key;
    key << "|segment";
    for (const std::int64_t id : a.labels)
        key << ' ' << id;
    if (a.range) key << " range " << (*a.range)[0] << ' ' << (*a.range)[1];
    return key.str();
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

const SceneFileCheck::Files& SceneFileCheck::filesOf(const Scene& scene) {
    const std::string key = filesKey(scene);
    auto it = m_files.find(key);
    if (it == m_files.end()) {
        Files files;
        files.key = key;
        try {
            // Sequential composition resamples the scan and drops its labels
            // (frameVolume): they are not read for such a frame.
            files.scan = std::make_shared<const Volume>(loadSceneVolume(scene, &files.nonFinite));
            if (!sequential(scene)) files.labels = loadSceneLabels(scene, files.scan);
        } catch (const InputError& e) {
            files.error = e.what(); // read once, reported for every frame that names them
        }
        it = m_files.emplace(key, std::move(files)).first;
    }
    if (!it->second.error.empty()) throw InputError(it->second.error);
    return it->second;
}

void SceneFileCheck::frame(const Scene& scene) {
    const Files& files = filesOf(scene);
    if (!sequential(scene)) {
        // What each frame's render refuses before it draws: overlapping
        // operators, a segment without voxels (its scan and labels as read).
        operators::checkNoOverlap(scene.operators);
        for (std::size_t i = 0; i < scene.operators.size(); ++i) {
            const OperatorSpec& op = scene.operators[i];
            if (op.alignment.mode != AlignmentMode::Segment) continue;
            // The message names the operator: one key per operator.
            const std::string key =
                files.key + segmentKey(op.alignment) + '|' + std::to_string(i) + ' ' + op.name;
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
    if (files.nonFinite > 0 && m_warnedFiles.insert(files.key).second)
        m_warnings.push_back(nonFiniteWarning(scene, files.nonFinite, files.scan->voxelCount()));
    const glm::dvec3 extent = files.scan->extent();
    for (OperatorOutside& o : operatorsOutside(scene, -0.5 * extent, 0.5 * extent))
        if (m_warned.insert(o.index).second) m_warnings.push_back(std::move(o.message));
}

} // namespace cutaway::job
