#pragma once
// View-aligned slicing (paper section 5): planes perpendicular to the view
// direction at a fixed spacing, each intersected with a convex proxy (the
// volume box) on the CPU. Only the covered polygon is rasterized: no
// full-screen quads with discard (on lavapipe those cost ~6x).
#include "render/camera.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace cutaway::render {

/// A convex polygon as a counter-clockwise or clockwise vertex loop.
using Polygon = std::vector<glm::dvec3>;

/// Clips a convex polygon against the half-space dot(n, p) <= d (Sutherland-Hodgman).
Polygon clipPolygon(const Polygon& polygon, glm::dvec3 n, double d);

/// The intersection of the plane dot(normal, p) = offset with `box` (empty if none).
Polygon slicePolygon(const Box& box, glm::dvec3 normal, double offset);

struct SliceSet {
    std::vector<glm::vec3> triangles; ///< triangle list, world space, front slice first
    int sliceCount = 0;
};

/// Slices `box` with planes perpendicular to `forward` every `spacing` mm, front
/// to back, on a lattice anchored at the world origin (s = (k + 0.5) * spacing)
/// so a moving box is not resampled differently. Planes with s <= minDepth
/// (in front of the near plane, measured from `eye` along forward) are skipped.
SliceSet buildSlices(const Box& box, glm::dvec3 eye, glm::dvec3 forward, double spacing,
                     double minDepth);

} // namespace cutaway::render
