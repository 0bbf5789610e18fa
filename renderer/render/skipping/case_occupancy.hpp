#pragma once
// Where in the world an operator's shader can show something, by the cases
// of Eq. 4 (shaders/shared/feature.h): a point left in place (p = p', where
// the feature mask M(p') >= 0.5: the volume at p') and a point that moves
// with the operator (p = p0, where M(p0) < 0.5: the volume at p0).
// operatorBlocks asks it about boxes: a block's points p', and the p0 its map
// can reach. Without the feature field both cases count wherever a brick is
// occupied; with it, only where the field's range over a cell of the ray
// caster's grid lets the case occur: a peel's opening is empty where its
// points are not the feature (M(p') < 0.5) and have no pre-image, though the
// volume there is occupied (docs/design/empty-space.md#operators-boxes).
#include "bake/feature_ranges.hpp"
#include "render/skipping/occupancy.hpp"

#include <cstdint>
#include <vector>

namespace cutaway::render {

class CaseOccupancy {
public:
    /// Both cases wherever `bricks` are occupied (kept by reference).
    explicit CaseOccupancy(const BrickOccupancy& bricks);
    /// Axis alignment (M = 0): nothing is left in place.
    static CaseOccupancy movedOnly(const BrickOccupancy& bricks);
    /// Surface or segment alignment: M >= 0.5 exactly where the feature field
    /// is `threshold` or more (surface: DT >= tau; segment: M itself, 0.5).
    /// `cells`: the values' spans over the same cells as `ranges`' (the ray
    /// caster's grid), `visible`: what the classification can show; where
    /// either is null, the ranges' bytes cannot tell the threshold apart or
    /// the grids differ, both cases count wherever a brick is occupied.
    /// `movedReadsNeighbours`: moved material reads a value one voxel
    /// further (segment alignment's movedValue), so the boxes asked about it
    /// grow by a voxel.
    static CaseOccupancy withFeature(const BrickOccupancy& bricks, const SpanGrid* cells,
                                     const VisibleValues* visible, const bake::FieldRanges* ranges,
                                     double threshold, bool movedReadsNeighbours);

    /// The smallest voxel spacing (mm): what the map's and the sampler's
    /// rounding may move a point by is half of it.
    double voxelMm() const;

    /// Whether a point left in place, in the world box [lo, hi], can show.
    bool keptMayShow(glm::dvec3 lo, glm::dvec3 hi) const;
    /// Whether a point that moved from the world box [lo, hi] can show.
    bool movedMayShow(glm::dvec3 lo, glm::dvec3 hi) const;

private:
    static constexpr uint8_t kKept = 1, kMoved = 2;
    bool anyCell(glm::dvec3 lo, glm::dvec3 hi, uint8_t flag) const;

    const BrickOccupancy* m_bricks;
    bool m_keeps = true;         ///< whether any point is left in place
    glm::dvec3 m_movedGrow{0.0}; ///< mm the boxes asked about moved points grow by
    /// Per cell (x fastest; none without the field): kKept | kMoved where
    /// that case can show a visible value there.
    glm::ivec3 m_cells{0};
    glm::dvec3 m_cellMm{0.0};
    std::vector<uint8_t> m_flags;
};

} // namespace cutaway::render
