#include "job/scene_check.hpp"

#include "job/render_job.hpp"
#include "mesh/mesh.hpp"
#include "operators/operator_geometry.hpp"

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

bool sequential(const Scene& scene) {
    return scene.render.composition == Composition::Sequential && scene.operators.size() > 1;
}

} // namespace

std::vector<std::string> checkSceneFiles(const std::vector<Scene>& frames) {
    std::vector<std::string> warnings;
    std::set<std::string> meshesRead;
    std::set<std::size_t> warned;
    std::map<std::string, glm::dvec3> extents; // by filesKey
    for (const Scene& scene : frames) {
        const std::string key = filesKey(scene);
        auto it = extents.find(key);
        if (it == extents.end()) {
            // Sequential composition resamples the scan and drops its labels
            // (frameVolume): they are not read for such a frame.
            auto scan = std::make_shared<const Volume>(loadSceneVolume(scene));
            if (!sequential(scene)) loadSceneLabels(scene, scan);
            it = extents.emplace(key, scan->extent()).first;
        }
        const glm::dvec3 extent = it->second;
        for (const MeshSpec& mesh : scene.meshes)
            if (meshesRead.insert(mesh.file.string()).second) mesh::loadGltf(mesh.file);
        for (OperatorOutside& o : operatorsOutside(scene, -0.5 * extent, 0.5 * extent))
            if (warned.insert(o.index).second) warnings.push_back(std::move(o.message));
    }
    return warnings;
}

} // namespace cutaway::job
