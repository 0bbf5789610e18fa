#pragma once
// The value material that moves with a segment-aligned operator reads at a
// voxel (movedValue in shaders/shared/feature_bake.h), on the CPU: the export
// samples it where the renderer samples bake/feature_region's texture, and
// the tests check that texture against it.
#include "shared/feature_bake.h"

#include <glm/glm.hpp>

namespace cutaway::operators {

/// At voxel `v` of a grid of `dims` (feature_region.comp does the same):
/// `value(x, y, z)` the volume, `mask(x, y, z)` M as the segment mask stores
/// it (inside: maskInside).
template <class Value, class Mask>
float movedValueAt(glm::ivec3 dims, glm::ivec3 v, Value&& value, Mask&& mask) {
    const float own = static_cast<float>(value(v.x, v.y, v.z));
    const bool inside = shader::maskInside(static_cast<float>(mask(v.x, v.y, v.z)));
    float sum = 0.0f, count = 0.0f;
    if (inside)
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::ivec3 n = v + glm::ivec3(dx, dy, dz);
                    if (glm::any(glm::lessThan(n, glm::ivec3(0))) ||
                        glm::any(glm::greaterThanEqual(n, dims)))
                        continue;
                    if (shader::maskInside(static_cast<float>(mask(n.x, n.y, n.z)))) continue;
                    sum += static_cast<float>(value(n.x, n.y, n.z));
                    count += 1.0f;
                }
    return shader::movedValue(own, inside, sum, count);
}

} // namespace cutaway::operators
