#include "operators/deformed_volume.hpp"

#include "operators/operator_geometry.hpp"
#include "shared/operators.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace cutaway::operators {
namespace {

// Trilinear interpolation of physical values at a world point (mm, origin at
// the volume's centre), clamped at the edge texels like the GPU sampler.
// Returns false outside the volume's box.
bool sample(const PlacedVolume& in, glm::dvec3 world, double& value) {
    const Volume& v = in.volume;
    const glm::dvec3 t = (world - in.worldLo) / v.extent();
    if (glm::any(glm::lessThan(t, glm::dvec3(0.0))) ||
        glm::any(glm::greaterThan(t, glm::dvec3(1.0))))
        return false;
    const glm::dvec3 p = t * glm::dvec3(v.dims) - 0.5;
    const glm::ivec3 i0 = glm::ivec3(glm::floor(p));
    const glm::dvec3 f = p - glm::dvec3(i0);
    value = 0.0;
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        const glm::ivec3 q = glm::clamp(i0 + o, glm::ivec3(0), v.dims - 1);
        const double w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
        if (w != 0.0) value += w * v.value(q.x, q.y, q.z);
    }
    return true;
}

} // namespace

PlacedVolume centred(Volume volume) {
    const glm::dvec3 lo = -0.5 * volume.extent();
    return PlacedVolume{std::move(volume), lo};
}

PlacedVolume resampleSequentially(const PlacedVolume& in,
                                  const std::vector<OperatorSpec>& operators, float emptyValue) {
    PlacedVolume current = in;
    for (const OperatorSpec& op : operators)
        current = resampleDeformed(current, {op}, emptyValue);
    return current;
}

PlacedVolume resampleDeformed(const PlacedVolume& in, const std::vector<OperatorSpec>& operators,
                              float emptyValue) {
    const Volume& volume = in.volume;
    struct Placed {
        const OperatorSpec* spec;
        WorldBox box;
        glm::dmat4 worldToLocal;
    };
    std::vector<Placed> placed;
    glm::dvec3 lo = in.worldLo, hi = in.worldLo + volume.extent();
    const glm::dvec3 volumeLo = lo;
    for (const OperatorSpec& op : operators) {
        const WorldBox box{op.localToWorld, materialBounds(op.params)};
        placed.push_back({&op, box, glm::inverse(op.localToWorld)});
        lo = glm::min(lo, box.lo());
        hi = glm::max(hi, box.hi());
    }
    // Whole voxels of the input grid, so untouched voxels land on themselves.
    const glm::dvec3 s = volume.spacing;
    const glm::dvec3 loVox = glm::floor((lo - volumeLo) / s + 1e-9);
    const glm::dvec3 hiVox = glm::ceil((hi - volumeLo) / s - 1e-9);
    lo = volumeLo + loVox * s;
    Volume out = Volume::allocate(glm::ivec3(hiVox - loVox), VoxelType::F32, s);
    out.origin = volume.origin + loVox * s;
    float* data = reinterpret_cast<float*>(out.data.data());

    for (int z = 0; z < out.dims.z; ++z)
        for (int y = 0; y < out.dims.y; ++y)
            for (int x = 0; x < out.dims.x; ++x) {
                glm::dvec3 p = lo + (glm::dvec3(x, y, z) + 0.5) * s;
                bool empty = false;
                for (const Placed& op : placed) {
                    const glm::dvec3 q(op.worldToLocal * glm::dvec4(p, 1.0));
                    if (glm::any(glm::lessThan(q, op.box.local.lo)) ||
                        glm::any(glm::greaterThan(q, op.box.local.hi)))
                        continue;
                    const glm::vec4 b = shader::operatorBackward(glm::vec3(q), op.spec->params);
                    empty = b.w <= 0.0f;
                    p = glm::dvec3(op.spec->localToWorld *
                                   glm::dvec4(glm::dvec3(glm::vec3(b)), 1.0));
                    break; // deformed boxes do not overlap
                }
                double value = 0.0;
                data[out.index(x, y, z)] =
                    !empty && sample(in, p, value) ? static_cast<float>(value) : emptyValue;
            }
    return PlacedVolume{std::move(out), lo};
}

} // namespace cutaway::operators
