#include "render/slicing/slicer.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

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

Proxy boxProxy(const Box& box) {
    return orientedBoxProxy(glm::dmat4(1.0), box.lo, box.hi);
}

Proxy orientedBoxProxy(const glm::dmat4& localToWorld, glm::dvec3 lo, glm::dvec3 hi) {
    // Local half-spaces q_i <= hi_i and -q_i <= -lo_i, with q = A^-1 (x - t):
    // row_i(A^-1) . x <= hi_i + row_i(A^-1) . t.
    Proxy proxy;
    const glm::dmat3 inv = glm::inverse(glm::dmat3(localToWorld));
    const glm::dvec3 t(localToWorld[3]);
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3 row(inv[0][i], inv[1][i], inv[2][i]);
        const double rt = glm::dot(row, t);
        proxy.halfSpaces.push_back({row, hi[i] + rt});
        proxy.halfSpaces.push_back({-row, -(lo[i] + rt)});
    }
    proxy.centre = glm::dvec3(localToWorld * glm::dvec4(0.5 * (lo + hi), 1.0));
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
        proxy.radius =
            std::max(proxy.radius,
                     glm::length(glm::dvec3(localToWorld * glm::dvec4(p, 1.0)) - proxy.centre));
    }
    return proxy;
}

Polygon slicePolygon(const Proxy& proxy, glm::dvec3 normal, double offset) {
    // Start from a square in the plane that covers the proxy, then clip it by
    // every face.
    const glm::dvec3 n = glm::normalize(normal);
    const glm::dvec3 c = proxy.centre;
    if (std::abs(offset - glm::dot(n, c)) > proxy.radius) return {};
    const glm::dvec3 p0 = c + (offset - glm::dot(n, c)) * n;
    const glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(n, a));
    const glm::dvec3 v = glm::cross(n, u);
    const double r = 2.0 * proxy.radius + 1.0;
    Polygon poly{p0 - r * u - r * v, p0 + r * u - r * v, p0 + r * u + r * v, p0 - r * u + r * v};
    for (const auto& h : proxy.halfSpaces) {
        poly = clipPolygon(poly, h.n, h.d);
        if (poly.empty()) break;
    }
    return poly.size() >= 3 ? poly : Polygon{};
}

SliceSet buildSlices(const std::vector<Proxy>& proxies, glm::dvec3 eye, glm::dvec3 forward,
                     double spacing, double minDepth) {
    SliceSet set;
    const glm::dvec3 f = glm::normalize(forward);
    double sMin = std::numeric_limits<double>::max(), sMax = -sMin;
    for (const Proxy& p : proxies) {
        sMin = std::min(sMin, glm::dot(f, p.centre) - p.radius);
        sMax = std::max(sMax, glm::dot(f, p.centre) + p.radius);
    }
    sMin = std::max(sMin, glm::dot(f, eye) + minDepth);
    if (!(sMin <= sMax)) return set;
    // Counted in integers: k += 1.0 would stop moving past 2^53.
    const auto kFirst = static_cast<long long>(std::ceil(sMin / spacing - 0.5));
    const auto kLast = static_cast<long long>(std::floor(sMax / spacing - 0.5));
    for (long long k = kFirst; k <= kLast; ++k) {
        const double s = (static_cast<double>(k) + 0.5) * spacing;
        std::vector<SliceDraw> draws;
        for (std::size_t i = 0; i < proxies.size(); ++i) {
            const Polygon poly = slicePolygon(proxies[i], f, s);
            if (poly.empty()) continue;
            SliceDraw draw{static_cast<int>(i), static_cast<uint32_t>(set.triangles.size()), 0};
            for (std::size_t v = 1; v + 1 < poly.size(); ++v) { // a fan: the polygon is convex
                set.triangles.emplace_back(poly[0]);
                set.triangles.emplace_back(poly[v]);
                set.triangles.emplace_back(poly[v + 1]);
            }
            draw.count = static_cast<uint32_t>(set.triangles.size()) - draw.first;
            draws.push_back(draw);
        }
        if (draws.empty()) continue;
        set.slices.push_back(std::move(draws));
        ++set.sliceCount;
    }
    return set;
}

void checkPlaneCount(const Box& bounds, double spacing, double sliceSpacing, double voxelMm) {
    // From the origin to the farthest corner, both ways: this also keeps the
    // lattice index k small enough for the ray caster's float loop counter.
    const double reach = std::max(glm::length(bounds.lo), glm::length(bounds.hi));
    const double planes = 2.0 * reach / spacing;
    if (std::isfinite(planes) && planes <= kMaxPlanes) return;
    std::ostringstream message;
    message << "/render/slice_spacing: " << sliceSpacing << " x the smallest voxel spacing ("
            << voxelMm << " mm) puts " << planes << " planes across the " << 2.0 * reach
            << " mm that the volume and its operators span; at most " << kMaxPlanes
            << " are drawn: raise /render/slice_spacing, place the operators nearer the volume, "
               "or check the volume's spacing";
    throw InputError(message.str());
}

} // namespace cutaway::render
