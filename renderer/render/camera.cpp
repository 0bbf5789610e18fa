#include "render/camera.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>

namespace cutaway::render {

glm::dvec3 orbitDirection(double azimuthDeg, double elevationDeg, glm::dvec3 up) {
    const glm::dvec3 w = glm::normalize(up);
    // A reference axis not parallel to up gives the frame (e1, e2, w); for up = +z
    // this is exactly (x, y, z).
    glm::dvec3 a = std::abs(w.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    glm::dvec3 e1 = glm::normalize(a - glm::dot(a, w) * w);
    glm::dvec3 e2 = glm::cross(w, e1);
    const double az = glm::radians(azimuthDeg), el = glm::radians(elevationDeg);
    return std::cos(el) * std::sin(az) * e1 - std::cos(el) * std::cos(az) * e2 + std::sin(el) * w;
}

namespace {

// The corners of `box` seen from a camera looking along -toEye with `up` at
// `target`: x right, y up, z towards the eye (a view's axes, about the target).
std::array<glm::dvec3, 8> cornersSeen(const Box& box, glm::dvec3 target, glm::dvec3 toEye,
                                      glm::dvec3 up) {
    const glm::dmat4 view = glm::lookAt(target + toEye, target, up);
    std::array<glm::dvec3, 8> corners;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p((i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y,
                           (i & 4) ? box.hi.z : box.lo.z);
        corners[std::size_t(i)] = glm::dvec3(view * glm::dvec4(p, 1.0)) + glm::dvec3(0, 0, 1);
    }
    return corners;
}

// The distance from the target at which every corner lies inside the
// frame, `margin` of its width and height kept free on each side: a corner
// (x, y, z) at depth D - z needs |x| <= kx (D - z) and |y| <= ky (D - z).
double tightDistance(const std::array<glm::dvec3, 8>& corners, double tanX, double tanY,
                     double margin) {
    const double kx = (1.0 - 2.0 * margin) * tanX, ky = (1.0 - 2.0 * margin) * tanY;
    double distance = 0.0;
    for (const glm::dvec3& c : corners)
        distance = std::max({distance, c.z + std::abs(c.x) / kx, c.z + std::abs(c.y) / ky});
    return distance;
}

// The orthographic height that holds every corner, `margin` kept free.
double tightHeight(const std::array<glm::dvec3, 8>& corners, double aspect, double margin) {
    double height = 0.0;
    for (const glm::dvec3& c : corners)
        height = std::max({height, 2.0 * std::abs(c.y), 2.0 * std::abs(c.x) / aspect});
    return height / (1.0 - 2.0 * margin);
}

} // namespace

CameraMatrices computeCamera(const Camera& camera, const Box& bounds, int width, int height,
                             const Box* alsoInDepth) {
    CameraMatrices m;
    const double aspect = static_cast<double>(width) / static_cast<double>(height);
    const double radius = std::max(bounds.radius(), 1e-12);
    const double fovY = glm::radians(camera.fovDeg);
    // The narrower of the two fields of view must hold the bounding sphere.
    const double fovX = 2.0 * std::atan(std::tan(fovY / 2.0) * aspect);
    const double fitDistance = radius / std::sin(std::min(fovX, fovY) / 2.0) * 1.05;

    // Directions given in LPS or RAS (Camera::directionsToVolume).
    const glm::dmat3& toVolume = camera.directionsToVolume;
    const glm::dvec3 target = camera.target;
    const glm::dvec3 up = toVolume * camera.up;
    glm::dvec3 eye = camera.eye;
    std::optional<std::array<glm::dvec3, 8>> seen; // with a margin: the corners as seen
    if (camera.useOrbit) {
        glm::dvec3 toEye = orbitDirection(camera.azimuthDeg, camera.elevationDeg, camera.up);
        if (toVolume != glm::dmat3(1.0)) toEye = glm::normalize(toVolume * toEye);
        if (camera.margin) seen = cornersSeen(bounds, target, toEye, up);
        double distance = camera.distance > 0.0 ? camera.distance : fitDistance;
        if (camera.distance <= 0.0 && seen)
            distance =
                tightDistance(*seen, std::tan(fovX / 2.0), std::tan(fovY / 2.0), *camera.margin);
        if (camera.distance <= 0.0) distance /= camera.zoom;
        if (camera.projection == Projection::Orthographic && camera.distance <= 0.0)
            distance = 3.0 * radius;
        eye = target + distance * toEye;
    }
    m.perspective = camera.projection == Projection::Perspective;
    m.eye = eye;
    m.forward = glm::normalize(target - eye);
    m.view = glm::lookAt(eye, target, up);

    // Depth range from the bounding sphere seen from the eye; slices carry no
    // depth yet, the planes only bound what is drawn.
    const double centreDepth = glm::dot(bounds.centre() - eye, m.forward);
    double nearest = centreDepth - 1.5 * radius, farthest = centreDepth + 1.5 * radius;
    if (alsoInDepth) {
        const double d = glm::dot(alsoInDepth->centre() - eye, m.forward);
        nearest = std::min(nearest, d - 1.05 * alsoInDepth->radius());
        farthest = std::max(farthest, d + 1.05 * alsoInDepth->radius());
    }
    // At least the volume's radius (not a fixed millimetre): a volume of
    // nanometre voxels lies well within 1 mm of the eye.
    const double farPlane = std::max(farthest, radius);
    if (m.perspective) {
        m.nearPlane = std::max(nearest, farPlane * 1e-3);
        m.proj = glm::perspective(fovY, aspect, m.nearPlane, farPlane);
    } else {
        m.nearPlane = nearest; // may be negative: ortho sees behind the eye
        const double fitted = seen ? tightHeight(*seen, aspect, *camera.margin)
                                   : 2.0 * radius * std::max(1.0, 1.0 / aspect);
        const double h = camera.orthoHeight > 0.0 ? camera.orthoHeight : fitted / camera.zoom;
        const double w = h * aspect;
        m.proj = glm::ortho(-w / 2, w / 2, -h / 2, h / 2, m.nearPlane, farPlane);
    }
    m.proj[1][1] *= -1.0; // Vulkan's clip y points down: keep world up at the top of the image
    m.viewProj = m.proj * m.view;
    return m;
}

} // namespace cutaway::render
