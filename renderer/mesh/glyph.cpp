// Built-in operator glyphs: a box's outline as 12 square bars.
#include "mesh/mesh.hpp"

#include <cmath>

namespace cutaway::mesh {
namespace {

// Appends the axis-aligned box [lo, hi] with 6 flat faces, 4 vertices each,
// wound counter-clockwise seen from outside.
void addBox(TriangleMesh& mesh, glm::vec3 lo, glm::vec3 hi, glm::vec4 color) {
    for (int axis = 0; axis < 3; ++axis) {
        // u x v = the axis, so corners (0,0) (1,0) (1,1) (0,1) in (u, v) run
        // counter-clockwise seen from the + side.
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            glm::vec3 normal(0.0f);
            normal[axis] = side == 0 ? -1.0f : 1.0f;
            glm::vec3 corners[4];
            const float uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (int c = 0; c < 4; ++c) {
                // The - side is seen from the other direction: reverse the order.
                const int k = side == 1 ? c : 3 - c;
                corners[c][axis] = side == 0 ? lo[axis] : hi[axis];
                corners[c][u] = uv[k][0] == 0 ? lo[u] : hi[u];
                corners[c][v] = uv[k][1] == 0 ? lo[v] : hi[v];
            }
            const auto base = static_cast<std::uint32_t>(mesh.positions.size());
            for (const glm::vec3& p : corners) {
                mesh.positions.push_back(p);
                mesh.normals.push_back(normal);
                mesh.colors.push_back(color);
            }
            for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u})
                mesh.indices.push_back(base + i);
        }
    }
}

} // namespace

TriangleMesh boxOutline(glm::vec3 lo, glm::vec3 hi, float width, glm::vec4 color) {
    // Tolerate swapped corners and a negative width rather than emit
    // inside-out bars.
    const glm::vec3 a = glm::min(lo, hi), b = glm::max(lo, hi);
    const float half = 0.5f * std::abs(width);

    TriangleMesh mesh;
    mesh.positions.reserve(12 * 24);
    mesh.normals.reserve(12 * 24);
    mesh.colors.reserve(12 * 24);
    mesh.indices.reserve(12 * 36);
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int corner = 0; corner < 4; ++corner) {
            // The edge along `axis` at one of the four (u, v) corners; the bar
            // runs half a width past both ends so bars meet in closed corners.
            glm::vec3 centre(0.0f);
            centre[u] = (corner & 1) ? b[u] : a[u];
            centre[v] = (corner & 2) ? b[v] : a[v];
            glm::vec3 barLo(0.0f), barHi(0.0f);
            barLo[axis] = a[axis] - half;
            barHi[axis] = b[axis] + half;
            for (int w : {u, v}) {
                barLo[w] = centre[w] - half;
                barHi[w] = centre[w] + half;
            }
            addBox(mesh, barLo, barHi, color);
        }
    }
    mesh.lo = a - glm::vec3(half);
    mesh.hi = b + glm::vec3(half);
    return mesh;
}

} // namespace cutaway::mesh
