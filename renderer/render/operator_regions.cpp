#include "render/operator_regions.hpp"

#include "shared/operators.h"

#include <algorithm>
#include <cmath>

namespace cutaway::render {
namespace {

// One texel of the baked map, as operator_bake.comp computes it.
struct Texel {
    glm::vec3 displacement; // pre-image minus the texel's position, local units
    float w;                // signed distance to the cut: <= 0 empty
};

std::vector<Texel> mapTexels(const OperatorSpec& spec, const operators::LocalBox& domain) {
    const glm::ivec3 res = spec.resolution;
    const glm::vec3 lo(domain.lo), hi(domain.hi);
    const shader::OperatorParams params = operators::sampledParams(spec.params, domain, res);
    std::vector<Texel> texels(std::size_t(res.x) * res.y * res.z);
    std::size_t i = 0;
    for (int z = 0; z < res.z; ++z)
        for (int y = 0; y < res.y; ++y)
            for (int x = 0; x < res.x; ++x, ++i) {
                const glm::vec3 q = glm::mix(lo, hi, (glm::vec3(x, y, z) + 0.5f) / glm::vec3(res));
                const glm::vec4 b = shader::operatorBackward(q, params);
                texels[i] = {glm::vec3(b) - q, b.w};
            }
    return texels;
}

// The world's axis-aligned bounds of the local box [lo, hi].
Box worldBounds(const glm::dmat4& localToWorld, glm::dvec3 lo, glm::dvec3 hi) {
    Box out{glm::dvec3(1e300), glm::dvec3(-1e300)};
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y,
                                (c & 4) ? hi.z : lo.z);
        const glm::dvec3 p(localToWorld * glm::dvec4(corner, 1.0));
        out.lo = glm::min(out.lo, p);
        out.hi = glm::max(out.hi, p);
    }
    return out;
}

} // namespace

double coverage(const std::vector<operators::LocalBox>& regions, const operators::LocalBox& box) {
    const auto volume = [](const operators::LocalBox& b) {
        const glm::dvec3 e = b.hi - b.lo;
        return e.x * e.y * e.z;
    };
    double covered = 0.0;
    for (const operators::LocalBox& r : regions)
        covered += volume(r);
    return covered / volume(box);
}

OperatorBlocks operatorBlocks(const OperatorSpec& spec, const operators::WorldBox& box,
                              const CaseOccupancy& cases, double reachMm) {
    const glm::ivec3 res = spec.resolution;
    const glm::dvec3 lo = box.local.lo, hi = box.local.hi;
    const glm::dvec3 texel = (hi - lo) / glm::dvec3(res);
    const std::vector<Texel> texels = mapTexels(spec, box.local);
    const auto texelAt = [&](int x, int y, int z) -> const Texel& {
        return texels[std::size_t(x) + std::size_t(res.x) * (y + std::size_t(res.y) * z)];
    };
    // The reach in local units along each axis (the frame may scale its axes).
    const glm::dmat3 axes(box.localToWorld);
    const glm::dvec3 reach(reachMm / glm::length(axes[0]), reachMm / glm::length(axes[1]),
                           reachMm / glm::length(axes[2]));
    // Rounding of the half-float map and of the sampler: half a voxel.
    const double pad = cases.voxelMm() * 0.5;

    const glm::ivec3 blocks = (res + (kOperatorBlockTexels - 1)) / kOperatorBlockTexels;
    OperatorBlocks result{blocks,
                          std::vector<uint8_t>(std::size_t(blocks.x) * blocks.y * blocks.z)};
    std::vector<uint8_t>& active = result.active;
    std::size_t index = 0;
    for (int bz = 0; bz < blocks.z; ++bz)
        for (int by = 0; by < blocks.y; ++by)
            for (int bx = 0; bx < blocks.x; ++bx, ++index) {
                const glm::ivec3 b(bx, by, bz);
                // The block's part of the box, and what the shader samples from it.
                const glm::dvec3 blockLo = lo + glm::dvec3(b * kOperatorBlockTexels) * texel;
                const glm::dvec3 blockHi =
                    glm::min(hi, lo + glm::dvec3((b + 1) * kOperatorBlockTexels) * texel);
                const glm::dvec3 spanLo = blockLo - reach, spanHi = blockHi + reach;
                // p' itself: a feature point left in place.
                const Box prime = worldBounds(box.localToWorld, spanLo, spanHi);
                if (cases.keptMayShow(prime.lo - pad, prime.hi + pad)) {
                    active[index] = 1;
                    continue;
                }
                // p0: q plus a trilinear blend of the displacements of the
                // texels whose centres bracket the span. Between texel
                // centres q is the same blend of the centres, so p0 is a
                // convex blend of the texels' own pre-images (centre plus
                // displacement): a rotating flap's p0 lie in the rotated
                // block, not in the block swept by every displacement. Where
                // the span passes the outermost centres the sampler clamps,
                // and p0 moves with q beyond them.
                const glm::ivec3 t0 = glm::clamp(
                    glm::ivec3(glm::floor((spanLo - lo) / texel - 0.5)), glm::ivec3(0), res - 1);
                const glm::ivec3 t1 = glm::clamp(glm::ivec3(glm::ceil((spanHi - lo) / texel - 0.5)),
                                                 glm::ivec3(0), res - 1);
                glm::dvec3 preLo(1e300), preHi(-1e300), dLo(1e300), dHi(-1e300);
                bool exists = false;
                for (int z = t0.z; z <= t1.z; ++z)
                    for (int y = t0.y; y <= t1.y; ++y)
                        for (int x = t0.x; x <= t1.x; ++x) {
                            const Texel& t = texelAt(x, y, z);
                            const glm::dvec3 centre = lo + (glm::dvec3(x, y, z) + 0.5) * texel;
                            const glm::dvec3 pre = centre + glm::dvec3(t.displacement);
                            preLo = glm::min(preLo, pre);
                            preHi = glm::max(preHi, pre);
                            dLo = glm::min(dLo, glm::dvec3(t.displacement));
                            dHi = glm::max(dHi, glm::dvec3(t.displacement));
                            exists = exists || t.w > 0.0f;
                        }
                if (!exists) continue; // all cut: no pre-image anywhere in the block
                const glm::dvec3 centreLo = lo + (glm::dvec3(t0) + 0.5) * texel;
                const glm::dvec3 centreHi = lo + (glm::dvec3(t1) + 0.5) * texel;
                // Both bounds hold; each is the tighter one somewhere (the
                // span plus every displacement where the map translates).
                const glm::dvec3 sourceLo =
                    glm::max(preLo - glm::max(centreLo - spanLo, glm::dvec3(0.0)), spanLo + dLo);
                const glm::dvec3 sourceHi =
                    glm::min(preHi + glm::max(spanHi - centreHi, glm::dvec3(0.0)), spanHi + dHi);
                const Box source = worldBounds(box.localToWorld, sourceLo, sourceHi);
                active[index] = cases.movedMayShow(source.lo - pad, source.hi + pad) ? 1 : 0;
            }

    return result;
}

std::vector<operators::LocalBox> operatorRegions(const OperatorBlocks& blocks,
                                                 const operators::WorldBox& box,
                                                 const OperatorSpec& spec) {
    const glm::dvec3 lo = box.local.lo, hi = box.local.hi;
    const glm::dvec3 texel = (hi - lo) / glm::dvec3(spec.resolution);
    std::vector<operators::LocalBox> regions;
    for (const CellRun& r : mergeCells(blocks.dims, blocks.active))
        regions.push_back({lo + glm::dvec3(r.lo * kOperatorBlockTexels) * texel,
                           glm::min(hi, lo + glm::dvec3(r.hi * kOperatorBlockTexels) * texel)});
    return regions;
}

std::vector<operators::LocalBox> operatorRegions(const OperatorSpec& spec,
                                                 const operators::WorldBox& box,
                                                 const BrickOccupancy& occupancy, double reachMm) {
    return operatorRegions(operatorBlocks(spec, box, CaseOccupancy(occupancy), reachMm), box, spec);
}

} // namespace cutaway::render
