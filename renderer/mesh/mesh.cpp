// TriangleMesh: concatenation with index offsets and bounds.
#include "mesh/mesh.hpp"

#include <cassert>

namespace cutaway::mesh {

void TriangleMesh::append(const TriangleMesh& other) {
    if (&other == this) {
        // Inserting a vector's own range into itself is undefined; copy first.
        const TriangleMesh copy = other;
        append(copy);
        return;
    }
    assert(other.normals.size() == other.positions.size());
    assert(other.colors.size() == other.positions.size());
    if (other.positions.empty()) return;

    const auto base = static_cast<std::uint32_t>(positions.size());
    // Bounds come from the appended positions rather than other.lo/hi, so a
    // mesh filled by hand without setting its bounds still appends correctly.
    glm::vec3 otherLo = other.positions.front(), otherHi = otherLo;
    for (const glm::vec3& p : other.positions) {
        otherLo = glm::min(otherLo, p);
        otherHi = glm::max(otherHi, p);
    }
    if (positions.empty()) {
        lo = otherLo;
        hi = otherHi;
    } else {
        lo = glm::min(lo, otherLo);
        hi = glm::max(hi, otherHi);
    }

    positions.insert(positions.end(), other.positions.begin(), other.positions.end());
    normals.insert(normals.end(), other.normals.begin(), other.normals.end());
    colors.insert(colors.end(), other.colors.begin(), other.colors.end());
    indices.reserve(indices.size() + other.indices.size());
    for (std::uint32_t i : other.indices)
        indices.push_back(base + i);
}

} // namespace cutaway::mesh
