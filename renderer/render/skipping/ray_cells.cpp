#include "render/skipping/ray_cells.hpp"

#include <algorithm>
#include <array>

namespace cutaway::render {

// Two raster passes of the 26-neighbour chamfer mask with unit weights, which
// is exact for this metric (a shortest chessboard path splits into steps the
// forward pass follows, then steps the backward pass follows), without the
// fronts a breadth-first search keeps. The grid is padded by a cell of kFar
// on every side, so a neighbour is an offset, never a bounds check (the cells
// of 2^3 voxels number an eighth of the voxels: 4 M on the frog).
std::vector<uint8_t> chessboardDistance(glm::ivec3 n, const std::vector<uint8_t>& flags) {
    constexpr uint8_t kFar = 255;
    const glm::ivec3 p = n + 2;
    const std::ptrdiff_t sx = 1, sy = p.x, sz = std::ptrdiff_t(p.x) * p.y;
    std::vector<uint8_t> padded(std::size_t(sz) * std::size_t(p.z), kFar);
    const auto at = [&](int x, int y, int z) { return (x + 1) * sx + (y + 1) * sy + (z + 1) * sz; };
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x)
                padded[std::size_t(at(x, y, z))] =
                    flags[std::size_t(x) + std::size_t(n.x) * (y + std::size_t(n.y) * z)] ? 0
                                                                                          : kFar;
    // Each pass takes a row at a time: first the 12 neighbours in the rows
    // already done (the row before, the slice before), which the compiler can
    // vectorize, then the one before in the row itself, in order.
    std::array<std::ptrdiff_t, 12> rowsBefore{};
    int count = 0;
    for (int dz = -1; dz <= 0; ++dz)
        for (int dy = -1; dy <= (dz < 0 ? 1 : -1); ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                rowsBefore[std::size_t(count++)] = dx * sx + dy * sy + dz * sz;
    const auto relaxRow = [&](uint8_t* row, std::ptrdiff_t sign) {
        for (const std::ptrdiff_t step : rowsBefore) {
            const uint8_t* from = row + sign * step;
            for (int x = 0; x < n.x; ++x) {
                const uint8_t v = from[x];
                row[x] = std::min(row[x], uint8_t(v + (v != kFar ? 1 : 0)));
            }
        }
        for (int i = 0; i < n.x; ++i) {
            const int x = sign > 0 ? i : n.x - 1 - i;
            const uint8_t v = row[x - sign];
            row[x] = std::min(row[x], uint8_t(v + (v != kFar ? 1 : 0)));
        }
    };
    uint8_t* d = padded.data();
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            relaxRow(d + at(0, y, z), 1);
    for (int z = n.z - 1; z >= 0; --z)
        for (int y = n.y - 1; y >= 0; --y)
            relaxRow(d + at(0, y, z), -1);
    std::vector<uint8_t> distance(flags.size());
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            std::copy_n(padded.begin() + at(0, y, z), n.x,
                        distance.begin() + std::ptrdiff_t(n.x) * (y + std::ptrdiff_t(n.y) * z));
    return distance;
}

std::vector<uint8_t> occupiedCells(const SpanGrid& spans, const VisibleValues& visible) {
    // Whether a span may show, by its two ends (kSpanSteps + 1 values each):
    // one lookup per cell instead of anyIn's arithmetic, for 4 M cells.
    std::vector<uint8_t> shows(std::size_t(kSpanSteps + 1) * (kSpanSteps + 1), 0);
    for (int lo = 0; lo <= kSpanSteps; ++lo)
        for (int hi = lo; hi <= kSpanSteps; ++hi) {
            const ValueSpan span{uint8_t(lo), uint8_t(hi)};
            shows[std::size_t(lo) * (kSpanSteps + 1) + std::size_t(hi)] =
                visible.anyIn(span.low(), span.high()) ? 1 : 0;
        }
    std::vector<uint8_t> flags(spans.spans.size(), 0);
    for (std::size_t i = 0; i < flags.size(); ++i) {
        const ValueSpan& s = spans.spans[i];
        flags[i] = shows[std::size_t(s.lo) * (kSpanSteps + 1) + s.hi];
    }
    return flags;
}

RayCells rayCells(const SpanGrid& spans, const VisibleValues& visible) {
    RayCells result;
    const glm::ivec3 n = spans.cells;
    result.cells = n;
    result.flags = occupiedCells(spans, visible);
    result.lo = n;
    result.hi = glm::ivec3(0);
    for (int cz = 0; cz < n.z; ++cz)
        for (int cy = 0; cy < n.y; ++cy)
            for (int cx = 0; cx < n.x; ++cx) {
                const std::size_t i =
                    std::size_t(cx) + std::size_t(n.x) * (cy + std::size_t(n.y) * cz);
                if (!result.flags[i]) continue;
                result.lo = glm::min(result.lo, glm::ivec3(cx, cy, cz));
                result.hi = glm::max(result.hi, glm::ivec3(cx, cy, cz) + 1);
            }
    if (glm::any(glm::greaterThanEqual(result.lo, result.hi)))
        result.lo = result.hi = glm::ivec3(0);
    result.distance = chessboardDistance(n, result.flags);
    return result;
}

SpanGrid brickSpans(const SpanGrid& cells) {
    if (cells.cellVoxels >= kBrickVoxels) return cells;
    SpanGrid bricks = coarsened(cells); // no copy of the (large) fine grid
    while (bricks.cellVoxels < kBrickVoxels)
        bricks = coarsened(bricks);
    return bricks;
}

RayCells rayCells(const Volume& scan, bake::ValueWindow window, const VisibleValues& visible,
                  int marginVoxels) {
    return rayCells(spanGrid(scan, window, kRayCellVoxels, 1 + marginVoxels), visible);
}

} // namespace cutaway::render
