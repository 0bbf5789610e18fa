#pragma once
// Empty-space skipping for operator proxies (docs/design/empty-space.md#operators-boxes). A point
// p' of an operator's deformed box shows something only where the volume can be seen at p' (a
// feature point left in place, Eq. 4) or at its pre-image p0 (Eq. 3). Over each cell between the
// baked map's texel centres, p0 is p' plus a trilinear blend of the eight corner texels'
// displacements, so it lies in the cell moved by the corners' smallest and largest displacement;
// and p0 exists only if some corner lies outside a cut (w > 0). A cell where neither box can show
// its case (CaseOccupancy: p' where a point is left in place, p0 where material moves; both
// wherever a brick is occupied unless the feature field's ranges say more) draws nothing. The other
// cells, grown by the reach of a slab (the shader also resolves the slab's back and middle), are
// merged into boxes of the operator's local frame: only these run the operator
// shader, while a cheap stencil-only pass still marks the whole box so the
// untouched volume is never drawn inside it.
#include "operators/operator_geometry.hpp"
#include "render/skipping/case_occupancy.hpp"
#include "render/skipping/occupancy.hpp"
#include "scene/scene.hpp"

#include <vector>

namespace cutaway::render {

using shader::kWholeBoxCoverage; // shared/tuning.h

/// The fraction of the box [lo, hi] that `regions` (inside it, disjoint) cover.
double coverage(const std::vector<operators::LocalBox>& regions, const operators::LocalBox& box);

using shader::kOperatorBlockTexels; // shared/tuning.h

/// The operator's box cut into blocks of kOperatorBlockTexels^3 map texels
/// (the last ones partial): a block is active where the operator shader can
/// produce a visible sample at a point of it, given where each case of Eq. 4
/// can show something (`cases`) and `reachMm` (how far from its point a
/// sample reads: a slab's length).
struct OperatorBlocks {
    glm::ivec3 dims{0};
    std::vector<uint8_t> active; ///< per block, x fastest: 1 active
};
OperatorBlocks operatorBlocks(const OperatorSpec& spec, const operators::WorldBox& box,
                              const CaseOccupancy& cases, double reachMm);

/// The active blocks merged into boxes of the operator's local frame.
std::vector<operators::LocalBox> operatorRegions(const OperatorBlocks& blocks,
                                                 const operators::WorldBox& box,
                                                 const OperatorSpec& spec);

/// Boxes of the operator's local frame, inside `box.local` and not
/// overlapping, that cover every point of its deformed box where the operator
/// shader can produce a visible sample, given the volume's `occupancy`;
/// `reachMm`: how far from a fragment the shader samples (a slab's length).
std::vector<operators::LocalBox> operatorRegions(const OperatorSpec& spec,
                                                 const operators::WorldBox& box,
                                                 const BrickOccupancy& occupancy, double reachMm);

} // namespace cutaway::render
