#pragma once
// Camera matrices from the scene's camera: world (mm, volume centre at the
// origin) -> Vulkan clip space, with image row 0 at the top and `up` pointing up.
#include "scene/scene.hpp"

#include <glm/glm.hpp>

namespace cutaway::render {

/// An axis-aligned box in world space (mm).
struct Box {
    glm::dvec3 lo{0.0};
    glm::dvec3 hi{0.0};
    glm::dvec3 centre() const { return 0.5 * (lo + hi); }
    double radius() const { return 0.5 * glm::length(hi - lo); }
};

struct CameraMatrices {
    glm::dmat4 view;     ///< world -> eye
    glm::dmat4 proj;     ///< eye -> clip (Vulkan: y down, depth 0..1)
    glm::dmat4 viewProj; ///< world -> clip
    glm::dvec3 eye;      ///< position (perspective) or a point behind the scene (orthographic)
    glm::dvec3 forward;  ///< unit view direction
    bool perspective = true;
    double nearPlane = 0.0;
};

/// Places the camera of `camera` for a `width` x `height` image looking at `bounds`
/// (distance or ortho height 0 = fit the bounding sphere of `bounds`). The depth
/// range covers `bounds` and, when given, `alsoInDepth` (meshes, which the
/// framing leaves out so that a long tool handle does not shrink the volume).
CameraMatrices computeCamera(const Camera& camera, const Box& bounds, int width, int height,
                             const Box* alsoInDepth = nullptr);

/// Unit direction from target to eye for an orbit (see scene.hpp for the convention).
glm::dvec3 orbitDirection(double azimuthDeg, double elevationDeg, glm::dvec3 up);

} // namespace cutaway::render
