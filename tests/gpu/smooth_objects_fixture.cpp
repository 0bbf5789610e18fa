#include "smooth_objects.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cutaway::test {
namespace {

constexpr glm::dvec3 kCentre{2.3, -1.7, 1.1}; // mm from the box's centre
constexpr glm::dvec3 kAxes{15.0, 12.0, 13.5}; // semi-axes, mm
constexpr double kEdge = 1.5;                 // mm, the smoothstep's width
constexpr double kBumpHeight = 1.0;           // mm, out and in from the ellipsoid
constexpr double kBumpWavelength = 8.0;       // mm

/// Signed distance to the ellipsoid's surface, positive inside, to first
/// order (exact on the surface).
double ellipsoidDistance(glm::dvec3 p) {
    const glm::dvec3 q = (p - kCentre) / kAxes;
    const double g = glm::dot(q, q);
    const double slope = glm::length(2.0 * q / kAxes);
    if (slope < 1e-9) return 1e9;
    return (1.0 - g) / slope;
}

double bumps(glm::dvec3 p) {
    const double k = 2.0 * std::numbers::pi / kBumpWavelength;
    return kBumpHeight * std::sin(k * p.x) * std::sin(k * p.y) * std::sin(k * p.z);
}

double smoothstepEdge(double inside) {
    const double t = std::clamp(inside / kEdge + 0.5, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

} // namespace

Volume sampleSmoothObject(SmoothObject object, glm::dvec3 spacing) {
    const glm::dvec3 count = kSmoothObjectBox / spacing;
    const glm::ivec3 dims(glm::round(count));
    if (glm::any(glm::greaterThan(glm::abs(count - glm::dvec3(dims)), glm::dvec3(1e-9))))
        throw std::invalid_argument("sampleSmoothObject: the spacing must divide the box");
    Volume v = Volume::allocate(dims, VoxelType::U8, spacing);
    auto* out = reinterpret_cast<std::uint8_t*>(v.data.data());
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const glm::dvec3 p = (glm::dvec3(x, y, z) + 0.5) * spacing - 0.5 * kSmoothObjectBox;
                double d = ellipsoidDistance(p);
                if (object == SmoothObject::Bumpy) d += bumps(p);
                out[v.index(x, y, z)] =
                    static_cast<std::uint8_t>(std::lround(200.0 * smoothstepEdge(d)));
            }
    return v;
}

Scene smoothObjectScene(int size, RenderMethod method) {
    Scene s;
    s.volume.window = std::array<double, 2>{0.0, 255.0};
    s.transfer.points = {{0.0, {0, 0, 0}, 0.0f},
                         {80.0, {0.85f, 0.8f, 0.75f}, 0.0f},
                         {120.0, {0.85f, 0.8f, 0.75f}, 1.0f},
                         {255.0, {0.85f, 0.8f, 0.75f}, 1.0f}};
    s.unitDistance = 1.0;
    s.camera.azimuthDeg = 35.0;
    s.camera.elevationDeg = 20.0;
    s.camera.zoom = 1.6;
    s.lights.directional = {{glm::dvec3(1.0, 0.4, -0.6), glm::vec3(1.0f), 0.5f}};
    s.render.width = s.render.height = size;
    s.render.background = glm::vec4(0.0f);
    s.render.method = method;
    s.render.sliceSpacing = 0.25; // of the smallest spacing: set per grid by the tests
    return s;
}

} // namespace cutaway::test
