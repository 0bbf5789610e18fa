#include "render/skipping/operator_regions.hpp"

#include "shared/operators.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace cutaway::render {
namespace {

// One texel of the baked map, as operator_bake.comp computes it.
struct Texel {
    glm::vec3 displacement; // pre-image minus the texel's position, local units
    float w;                // signed distance to the cut plus its margin (cutMarginCap): <= 0 empty
};

std::vector<Texel> mapTexels(const OperatorSpec& spec, const operators::LocalBox& domain) {
    const glm::ivec3 res = spec.resolution;
    const glm::vec3 lo(domain.lo), hi(domain.hi);
    const shader::OperatorParams params = operators::sampledParams(spec.params, domain, res);
    // A sample within the margin beyond a cut may show part of the material
    // (operator_sample.h, resolve).
    const auto margin = static_cast<float>(operators::cutMarginCap(spec, domain));
    std::vector<Texel> texels(std::size_t(res.x) * res.y * res.z);
    std::size_t i = 0;
    for (int z = 0; z < res.z; ++z)
        for (int y = 0; y < res.y; ++y)
            for (int x = 0; x < res.x; ++x, ++i) {
                const glm::vec3 q = glm::mix(lo, hi, (glm::vec3(x, y, z) + 0.5f) / glm::vec3(res));
                const glm::vec4 b = shader::operatorBackward(q, params);
                texels[i] = {glm::vec3(b) - q, b.w + margin};
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

// The extremes of the map's texels over a box of them: their pre-images
// (centre plus displacement), their displacements, and whether any lies
// outside a cut (w > 0).
struct Extremes {
    glm::dvec3 preLo{1e300}, preHi{-1e300};
    glm::vec3 dLo{1e30f}, dHi{-1e30f}; // the texels' own floats: exact
    bool exists = false;
    void take(const Extremes& o) {
        preLo = glm::min(preLo, o.preLo);
        preHi = glm::max(preHi, o.preHi);
        dLo = glm::min(dLo, o.dLo);
        dHi = glm::max(dHi, o.dHi);
        exists = exists || o.exists;
    }
};

// Per slice z of the map and block column (bx, by): the Extremes of the
// texels [first[0][bx], last[0][bx]] x [first[1][by], last[1][by]] of that
// slice, x fastest, then by, then z. A block's Extremes are those of its
// slices [first[2][bz], last[2][bz]] (operatorBlocks takes those): a box's
// extremes are the extremes of its rows', so passes of one axis each replace
// a walk over every block's whole bracket, which for long slabs spans many
// texels (at d = 6 about 14^3 a block: a third of a second an operator, ten
// times that under the sanitizers).
std::vector<Extremes> sliceExtremes(const std::vector<Texel>& texels, glm::ivec3 res,
                                    glm::ivec3 blocks, glm::dvec3 lo, glm::dvec3 texel,
                                    const std::array<std::vector<int>, 3>& first,
                                    const std::array<std::vector<int>, 3>& last) {
    std::vector<Extremes> slices(std::size_t(blocks.x) * blocks.y * res.z);
    std::vector<Extremes> rows(std::size_t(blocks.x) * res.y); // one slice's, x reduced
    for (int z = 0; z < res.z; ++z) {
        for (int y = 0; y < res.y; ++y)
            for (int bx = 0; bx < blocks.x; ++bx) {
                Extremes& e = rows[std::size_t(bx) + std::size_t(blocks.x) * y];
                e = {};
                for (int x = first[0][bx]; x <= last[0][bx]; ++x) {
                    const Texel& t =
                        texels[std::size_t(x) + std::size_t(res.x) * (y + std::size_t(res.y) * z)];
                    const glm::dvec3 pre =
                        lo + (glm::dvec3(x, y, z) + 0.5) * texel + glm::dvec3(t.displacement);
                    e.take({pre, pre, t.displacement, t.displacement, t.w > 0.0f});
                }
            }
        for (int by = 0; by < blocks.y; ++by)
            for (int bx = 0; bx < blocks.x; ++bx) {
                Extremes& e = slices[std::size_t(bx) +
                                     std::size_t(blocks.x) * (by + std::size_t(blocks.y) * z)];
                for (int y = first[1][by]; y <= last[1][by]; ++y)
                    e.take(rows[std::size_t(bx) + std::size_t(blocks.x) * y]);
            }
    }
    return slices;
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
    // Along each axis, each block's part of the box, the span a sample there
    // reads, and the texels whose centres bracket the span.
    std::array<std::vector<double>, 3> spanLo, spanHi;
    std::array<std::vector<int>, 3> first, last;
    for (int axis = 0; axis < 3; ++axis)
        for (int b = 0; b < blocks[axis]; ++b) {
            const double blockLo = lo[axis] + double(b * kOperatorBlockTexels) * texel[axis];
            const double blockHi =
                std::min(hi[axis], lo[axis] + double((b + 1) * kOperatorBlockTexels) * texel[axis]);
            spanLo[axis].push_back(blockLo - reach[axis]);
            spanHi[axis].push_back(blockHi + reach[axis]);
            first[axis].push_back(
                std::clamp(int(std::floor((spanLo[axis][b] - lo[axis]) / texel[axis] - 0.5)), 0,
                           res[axis] - 1));
            last[axis].push_back(
                std::clamp(int(std::ceil((spanHi[axis][b] - lo[axis]) / texel[axis] - 0.5)), 0,
                           res[axis] - 1));
        }
    const std::vector<Extremes> slices = sliceExtremes(texels, res, blocks, lo, texel, first, last);

    std::size_t index = 0;
    for (int bz = 0; bz < blocks.z; ++bz)
        for (int by = 0; by < blocks.y; ++by)
            for (int bx = 0; bx < blocks.x; ++bx, ++index) {
                const glm::dvec3 spanLoB(spanLo[0][bx], spanLo[1][by], spanLo[2][bz]);
                const glm::dvec3 spanHiB(spanHi[0][bx], spanHi[1][by], spanHi[2][bz]);
                // p' itself: a feature point left in place.
                const Box prime = worldBounds(box.localToWorld, spanLoB, spanHiB);
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
                const glm::ivec3 t0(first[0][bx], first[1][by], first[2][bz]);
                const glm::ivec3 t1(last[0][bx], last[1][by], last[2][bz]);
                Extremes e;
                for (int z = t0.z; z <= t1.z; ++z)
                    e.take(slices[std::size_t(bx) +
                                  std::size_t(blocks.x) * (by + std::size_t(blocks.y) * z)]);
                if (!e.exists) continue; // all cut: no pre-image anywhere in the block
                const glm::dvec3 centreLo = lo + (glm::dvec3(t0) + 0.5) * texel;
                const glm::dvec3 centreHi = lo + (glm::dvec3(t1) + 0.5) * texel;
                // Both bounds hold; each is the tighter one somewhere (the
                // span plus every displacement where the map translates).
                const glm::dvec3 sourceLo =
                    glm::max(e.preLo - glm::max(centreLo - spanLoB, glm::dvec3(0.0)),
                             spanLoB + glm::dvec3(e.dLo));
                const glm::dvec3 sourceHi =
                    glm::min(e.preHi + glm::max(spanHiB - centreHi, glm::dvec3(0.0)),
                             spanHiB + glm::dvec3(e.dHi));
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
