#include "render/skipping/case_occupancy.hpp"

#include "render/skipping/ray_cells.hpp"

#include <cmath>

namespace cutaway::render {

CaseOccupancy::CaseOccupancy(const BrickOccupancy& bricks) : m_bricks(&bricks) {}

CaseOccupancy CaseOccupancy::movedOnly(const BrickOccupancy& bricks) {
    CaseOccupancy c(bricks);
    c.m_keeps = false;
    return c;
}

CaseOccupancy CaseOccupancy::withFeature(const BrickOccupancy& bricks, const SpanGrid* cells,
                                         const VisibleValues* visible,
                                         const bake::FieldRanges* ranges, double threshold,
                                         bool movedReadsNeighbours) {
    CaseOccupancy c(bricks);
    if (movedReadsNeighbours) c.m_movedGrow = bricks.brickMm / double(kBrickVoxels);
    if (!cells || !visible || !ranges || cells->cells != ranges->cells ||
        cells->cellVoxels != ranges->cellVoxels || !ranges->resolves(threshold))
        return c;
    c.m_cells = cells->cells;
    c.m_cellMm = bricks.brickMm * (double(cells->cellVoxels) / double(kBrickVoxels));
    c.m_flags = occupiedCells(*cells, *visible);
    for (std::size_t i = 0; i < c.m_flags.size(); ++i)
        if (c.m_flags[i])
            c.m_flags[i] = uint8_t((ranges->mayReach(i, threshold) ? kKept : 0) |
                                   (ranges->mayBeBelow(i, threshold) ? kMoved : 0));
    return c;
}

double CaseOccupancy::voxelMm() const {
    const glm::dvec3 b = m_bricks->brickMm;
    return glm::min(b.x, glm::min(b.y, b.z)) / double(kBrickVoxels);
}

bool CaseOccupancy::keptMayShow(glm::dvec3 lo, glm::dvec3 hi) const {
    return m_keeps && anyCell(lo, hi, kKept);
}

bool CaseOccupancy::movedMayShow(glm::dvec3 lo, glm::dvec3 hi) const {
    return anyCell(lo - m_movedGrow, hi + m_movedGrow, kMoved);
}

bool CaseOccupancy::anyCell(glm::dvec3 lo, glm::dvec3 hi, uint8_t flag) const {
    if (!m_bricks->anyIn(lo, hi)) return false; // in O(1), and no cell is occupied without it
    if (m_flags.empty()) return true;
    const Box& box = m_bricks->box;
    const glm::ivec3 last = m_cells - 1;
    const glm::ivec3 a =
        glm::clamp(glm::ivec3(glm::floor((lo - box.lo) / m_cellMm)), glm::ivec3(0), last);
    const glm::ivec3 b =
        glm::clamp(glm::ivec3(glm::floor((hi - box.lo) / m_cellMm)), glm::ivec3(0), last);
    for (int z = a.z; z <= b.z; ++z)
        for (int y = a.y; y <= b.y; ++y) {
            const std::size_t row = std::size_t(m_cells.x) * (y + std::size_t(m_cells.y) * z);
            for (int x = a.x; x <= b.x; ++x)
                if (m_flags[row + std::size_t(x)] & flag) return true;
        }
    return false;
}

} // namespace cutaway::render
