#pragma once
// Empty-space skipping for the ray caster (docs/design/empty-space.md). The volume is
// cut into cells of kRayCellVoxels^3; a cell is empty when the classification
// gives no opacity to any value that a sample in the cell, or a slab up to the
// margin long that starts there, can read (as for the bricks, occupancy.hpp). A ray at a sample in
// an empty cell may jump to its first sample outside the cell: every sample and slab it passes over
// is transparent. Finer and tighter than the slicing proxies' bricks (occupancy.hpp), which must
// cover slabs a brick long and stay few polygons. So that rays cross open air in a few long jumps
// instead of one per cell, each empty cell also carries its chessboard distance r to the nearest
// occupied cell: the cube of cells within r - 1 of it is empty, and a ray may
// jump to that cube's wall.
#include "render/skipping/occupancy.hpp"

namespace cutaway::render {

using shader::kRayCellVoxels; // shared/tuning.h

struct RayCells {
    glm::ivec3 cells{0};
    std::vector<uint8_t> flags; ///< per cell, x fastest: 1 occupied
    /// Per cell: 0 when occupied, else the chessboard distance (in cells, at
    /// most 255) to the nearest occupied cell; 255 everywhere when none is.
    std::vector<uint8_t> distance;
    /// The occupied cells' bounds, cells [lo, hi); lo == hi when none is.
    glm::ivec3 lo{0}, hi{0};
};

/// Per cell of a grid of `n` cells (x fastest): 0 where `flags` is set, else
/// the chessboard (L-infinity) distance in cells to the nearest set one, at
/// most 255 (255 everywhere when none is).
std::vector<uint8_t> chessboardDistance(glm::ivec3 n, const std::vector<uint8_t>& flags);

/// The slicing bricks' spans (kBrickVoxels) from the ray caster's cells'
/// with the same reach: their 2x2x2 unions, taken until the cells are bricks.
SpanGrid brickSpans(const SpanGrid& cells);

/// Per cell of `spans` (x fastest), 1 where some value it spans can show
/// (`visible`), else 0.
std::vector<uint8_t> occupiedCells(const SpanGrid& spans, const VisibleValues& visible);

/// The cells whose spans (kRayCellVoxels cells reaching 1 + the margin) are
/// `spans`, where `visible` says which values can show.
RayCells rayCells(const SpanGrid& spans, const VisibleValues& visible);

/// The same from the scan, for values normalized over `window`, with a margin
/// of `marginVoxels` voxels.
RayCells rayCells(const Volume& scan, bake::ValueWindow window, const VisibleValues& visible,
                  int marginVoxels);

} // namespace cutaway::render
