#pragma once
// View-aligned slicing (paper section 5): planes perpendicular to the view
// direction at a fixed spacing, each intersected on the CPU with every convex
// proxy (the volume box, and each operator's deformed box, section 5.1). Only
// the covered polygons are rasterized: no full-screen quads with discard (on
// lavapipe those cost ~6x).
#include "render/camera.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace cutaway::render {

/// A convex polygon as a vertex loop.
using Polygon = std::vector<glm::dvec3>;

/// Clips a convex polygon against the half-space dot(n, p) <= d (Sutherland-Hodgman).
Polygon clipPolygon(const Polygon& polygon, glm::dvec3 n, double d);

/// A convex region as the intersection of half-spaces dot(n, p) <= d.
struct Proxy {
    struct HalfSpace {
        glm::dvec3 n;
        double d;
    };
    std::vector<HalfSpace> halfSpaces;
    glm::dvec3 centre{0.0};
    double radius = 0.0; ///< of a sphere that contains the region
};

/// An axis-aligned box.
Proxy boxProxy(const Box& box);
/// The box [lo, hi] of a local frame placed in the world by an affine map.
Proxy orientedBoxProxy(const glm::dmat4& localToWorld, glm::dvec3 lo, glm::dvec3 hi);

/// The intersection of the plane dot(normal, p) = offset with the proxy (empty if none).
Polygon slicePolygon(const Proxy& proxy, glm::dvec3 normal, double offset);

/// Triangles of one proxy on one slice: [first, first + count) of SliceSet::triangles.
struct SliceDraw {
    int proxy = 0; ///< index into the proxies given to buildSlices
    uint32_t first = 0;
    uint32_t count = 0;
};

struct SliceSet {
    std::vector<glm::vec3> triangles;           ///< triangle list, world space, front slice first
    std::vector<std::vector<SliceDraw>> slices; ///< per slice, front to back: its polygons
    int sliceCount = 0;
};

/// Slices every proxy with planes perpendicular to `forward` every `spacing`
/// mm, front to back, on one lattice anchored at the world origin
/// (s = (k + 0.5) * spacing) so that proxies share planes and a moving proxy
/// is not resampled differently. Planes at depth <= minDepth (in front of the
/// near plane, measured from `eye` along forward) are skipped. Within a slice,
/// draws keep the order of `proxies`.
SliceSet buildSlices(const std::vector<Proxy>& proxies, glm::dvec3 eye, glm::dvec3 forward,
                     double spacing, double minDepth);

/// Most planes a frame may need across what it draws; with a voxel spacing of
/// 1e-30 mm in a file, the lattice would otherwise have 10^31 planes and the
/// frame would never end.
inline constexpr double kMaxPlanes = 65536.0;

/// Throws InputError naming /render/slice_spacing when planes every
/// `spacing` mm (`sliceSpacing` times the smallest voxel spacing `voxelMm`)
/// over a lattice anchored at the origin would number more than kMaxPlanes
/// across `bounds` (world space, anywhere relative to the origin).
void checkPlaneCount(const Box& bounds, double spacing, double sliceSpacing, double voxelMm);

} // namespace cutaway::render
