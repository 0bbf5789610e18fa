#include "job/volume_frame.hpp"

#include "core/error.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace cutaway::job {

namespace {

const char* nameOf(CoordinateSpace space) {
    return space == CoordinateSpace::RAS ? "ras" : "lps";
}

std::string scanNameOf(const Scene& scene) {
    return scene.volume.phantom.empty() ? scene.volume.file.string()
                                        : "the phantom \"" + scene.volume.phantom + "\"";
}

} // namespace

glm::dmat4 spaceToVolumeFrame(const Volume& scan, CoordinateSpace space, const std::string& pointer,
                              const std::string& scanName) {
    if (space == CoordinateSpace::Volume) return glm::dmat4(1.0);
    if (scan.space != Space::LPS)
        throw InputError(pointer + ": \"" + nameOf(space) + "\" needs the scan's patient " +
                         "coordinates, and " + scanName +
                         (scan.space == Space::None
                              ? " gives none (no NIfTI qform or sform, NRRD space or DICOM "
                                "patient position)"
                              : " gives a space with no anatomical meaning") +
                         ": place it in \"volume\" coordinates (mm from the volume's centre)");
    // LPS -> voxel offsets along the grid's axes -> the volume frame.
    const glm::dvec3 shift = 0.5 * scan.spacing - 0.5 * scan.extent();
    glm::dmat4 toVolume = glm::translate(glm::dmat4(1.0), shift) *
                          glm::dmat4(glm::inverse(scan.direction)) *
                          glm::translate(glm::dmat4(1.0), -scan.origin);
    if (space == CoordinateSpace::RAS)
        toVolume = toVolume * glm::scale(glm::dmat4(1.0), glm::dvec3(-1.0, -1.0, 1.0));
    return toVolume;
}

bool placedInScanSpace(const Scene& scene) {
    bool any = scene.camera.space != CoordinateSpace::Volume;
    for (const OperatorSpec& op : scene.operators)
        any = any || op.space != CoordinateSpace::Volume;
    for (const MeshSpec& mesh : scene.meshes)
        any = any || mesh.space != CoordinateSpace::Volume;
    return any;
}

Scene inVolumeFrame(const Scene& scene, const Volume& scan) {
    Scene placed = scene;
    if (!placedInScanSpace(scene)) return placed;
    const std::string scanName = scanNameOf(scene);
    for (OperatorSpec& op : placed.operators) {
        const std::string pointer = "/operators/" + std::to_string(op.index) + "/placement/space";
        op.localToWorld = spaceToVolumeFrame(scan, op.space, pointer, scanName) * op.localToWorld;
        op.space = CoordinateSpace::Volume;
    }
    for (std::size_t i = 0; i < placed.meshes.size(); ++i) {
        MeshSpec& mesh = placed.meshes[i];
        const std::string pointer = "/meshes/" + std::to_string(i) + "/placement/space";
        mesh.placement = spaceToVolumeFrame(scan, mesh.space, pointer, scanName) * mesh.placement;
        mesh.space = CoordinateSpace::Volume;
    }
    Camera& camera = placed.camera;
    if (camera.space != CoordinateSpace::Volume) {
        const std::string pointer =
            std::string("/camera/") + (camera.useOrbit ? "orbit" : "look_at") + "/space";
        const glm::dmat4 m = spaceToVolumeFrame(scan, camera.space, pointer, scanName);
        if (camera.targetGiven) camera.target = glm::dvec3(m * glm::dvec4(camera.target, 1.0));
        camera.eye = glm::dvec3(m * glm::dvec4(camera.eye, 1.0));
        camera.directionsToVolume = glm::dmat3(m);
        camera.space = CoordinateSpace::Volume;
    }
    return placed;
}

Volume geometryOf(const Volume& scan) {
    Volume g;
    g.dims = scan.dims;
    g.spacing = scan.spacing;
    g.origin = scan.origin;
    g.direction = scan.direction;
    g.space = scan.space;
    g.type = scan.type;
    return g;
}

} // namespace cutaway::job
