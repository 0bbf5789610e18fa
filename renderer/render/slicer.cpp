#include "render/slicer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cutaway::render {

Polygon clipPolygon(const Polygon& polygon, glm::dvec3 n, double d) {
    Polygon out;
    const std::size_t count = polygon.size();
    for (std::size_t i = 0; i < count; ++i) {
        const glm::dvec3& a = polygon[i];
        const glm::dvec3& b = polygon[(i + 1) % count];
        const double da = glm::dot(n, a) - d, db = glm::dot(n, b) - d;
        if (da <= 0.0) out.push_back(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0))
            out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

Polygon slicePolygon(const Box& box, glm::dvec3 normal, double offset) {
    // Start from a square in the plane that covers the box, then clip it by the
    // six faces. Generalizes to any convex proxy (bricks, deformed boxes).
    const glm::dvec3 n = glm::normalize(normal);
    const glm::dvec3 c = box.centre();
    const glm::dvec3 p0 = c + (offset - glm::dot(n, c)) * n;
    const glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(n, a));
    const glm::dvec3 v = glm::cross(n, u);
    const double r = 2.0 * box.radius() + 1.0;
    Polygon poly{p0 - r * u - r * v, p0 + r * u - r * v, p0 + r * u + r * v, p0 - r * u + r * v};
    for (int axis = 0; axis < 3 && !poly.empty(); ++axis) {
        glm::dvec3 e(0.0);
        e[axis] = 1.0;
        poly = clipPolygon(poly, e, box.hi[axis]);
        if (!poly.empty()) poly = clipPolygon(poly, -e, -box.lo[axis]);
    }
    return poly.size() >= 3 ? poly : Polygon{};
}

SliceSet buildSlices(const Box& box, glm::dvec3 eye, glm::dvec3 forward, double spacing,
                     double minDepth) {
    SliceSet set;
    const glm::dvec3 f = glm::normalize(forward);
    double sMin = std::numeric_limits<double>::max(), sMax = -sMin;
    for (int i = 0; i < 8; ++i) {
        glm::dvec3 corner((i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y,
                          (i & 4) ? box.hi.z : box.lo.z);
        const double s = glm::dot(f, corner);
        sMin = std::min(sMin, s);
        sMax = std::max(sMax, s);
    }
    sMin = std::max(sMin, glm::dot(f, eye) + minDepth);
    const double kFirst = std::ceil(sMin / spacing - 0.5);
    for (double k = kFirst;; k += 1.0) {
        const double s = (k + 0.5) * spacing;
        if (s > sMax) break;
        Polygon poly = slicePolygon(box, f, s);
        if (poly.empty()) continue;
        for (std::size_t i = 1; i + 1 < poly.size(); ++i) { // a fan: the polygon is convex
            set.triangles.emplace_back(poly[0]);
            set.triangles.emplace_back(poly[i]);
            set.triangles.emplace_back(poly[i + 1]);
        }
        ++set.sliceCount;
    }
    return set;
}

} // namespace cutaway::render
