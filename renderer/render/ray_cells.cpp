#include "render/ray_cells.hpp"

#include <algorithm>

namespace cutaway::render {
namespace {

// The chessboard (L-infinity) distance from each cell to the nearest flagged
// one: a breadth-first search from all of them over the 26 neighbours.
std::vector<uint8_t> chessboardDistance(glm::ivec3 n, const std::vector<uint8_t>& flags) {
    constexpr int kFar = 255;
    std::vector<uint8_t> distance(flags.size(), uint8_t(kFar));
    std::vector<glm::ivec3> front;
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x)
                if (flags[std::size_t(x) + std::size_t(n.x) * (y + std::size_t(n.y) * z)]) {
                    distance[std::size_t(x) + std::size_t(n.x) * (y + std::size_t(n.y) * z)] = 0;
                    front.push_back({x, y, z});
                }
    for (int d = 1; d < kFar && !front.empty(); ++d) {
        std::vector<glm::ivec3> next;
        for (const glm::ivec3 c : front)
            for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const glm::ivec3 q = c + glm::ivec3(dx, dy, dz);
                        if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
                            glm::any(glm::greaterThanEqual(q, n)))
                            continue;
                        uint8_t& at = distance[std::size_t(q.x) +
                                               std::size_t(n.x) * (q.y + std::size_t(n.y) * q.z)];
                        if (at != kFar) continue;
                        at = uint8_t(d);
                        next.push_back(q);
                    }
        front = std::move(next);
    }
    return distance;
}

} // namespace

RayCells rayCells(const Volume& scan, bake::ValueWindow window, const VisibleValues& visible,
                  int marginVoxels) {
    RayCells result;
    const glm::ivec3 n = (scan.dims + (kRayCellVoxels - 1)) / kRayCellVoxels;
    result.cells = n;
    const std::vector<ValueSpan> grid = cellRanges(scan, window, kRayCellVoxels, 1 + marginVoxels);
    result.flags.assign(grid.size(), 0);
    result.lo = n;
    result.hi = glm::ivec3(0);
    for (int cz = 0; cz < n.z; ++cz)
        for (int cy = 0; cy < n.y; ++cy)
            for (int cx = 0; cx < n.x; ++cx) {
                const std::size_t i =
                    std::size_t(cx) + std::size_t(n.x) * (cy + std::size_t(n.y) * cz);
                if (grid[i].lo > grid[i].hi || !visible.anyIn(grid[i].lo, grid[i].hi)) continue;
                result.flags[i] = 1;
                result.lo = glm::min(result.lo, glm::ivec3(cx, cy, cz));
                result.hi = glm::max(result.hi, glm::ivec3(cx, cy, cz) + 1);
            }
    if (glm::any(glm::greaterThanEqual(result.lo, result.hi)))
        result.lo = result.hi = glm::ivec3(0);
    result.distance = chessboardDistance(n, result.flags);
    return result;
}

} // namespace cutaway::render
