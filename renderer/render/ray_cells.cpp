#include "render/ray_cells.hpp"

#include <algorithm>
#include <array>

namespace cutaway::render {

// Two raster passes of the 26-neighbour chamfer mask with unit weights, which
// is exact for this metric (a shortest chessboard path splits into steps the
// forward pass follows, then steps the backward pass follows), in place and
// without the fronts a breadth-first search keeps.
std::vector<uint8_t> chessboardDistance(glm::ivec3 n, const std::vector<uint8_t>& flags) {
    constexpr int kFar = 255;
    std::vector<uint8_t> distance(flags.size());
    std::transform(flags.begin(), flags.end(), distance.begin(),
                   [](uint8_t f) { return uint8_t(f ? 0 : kFar); });
    // The 13 neighbours that come before a cell in raster order (x fastest).
    std::array<glm::ivec3, 13> before{};
    int count = 0;
    for (int dz = -1; dz <= 0; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (dz < 0 || dy < 0 || (dy == 0 && dx < 0))
                    before[std::size_t(count++)] = {dx, dy, dz};
    const auto at = [&](glm::ivec3 c) -> uint8_t& {
        return distance[std::size_t(c.x) + std::size_t(n.x) * (c.y + std::size_t(n.y) * c.z)];
    };
    const auto relax = [&](glm::ivec3 c, int sign) {
        uint8_t& d = at(c);
        for (const glm::ivec3 step : before) {
            const glm::ivec3 q = c + sign * step;
            if (glm::any(glm::lessThan(q, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(q, n)))
                continue;
            d = uint8_t(std::min(int(d), std::min(int(at(q)) + 1, kFar)));
        }
    };
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x)
                relax({x, y, z}, 1);
    for (int z = n.z - 1; z >= 0; --z)
        for (int y = n.y - 1; y >= 0; --y)
            for (int x = n.x - 1; x >= 0; --x)
                relax({x, y, z}, -1);
    return distance;
}

RayCells rayCells(const SpanGrid& spans, const VisibleValues& visible) {
    RayCells result;
    const glm::ivec3 n = spans.cells;
    result.cells = n;
    result.flags.assign(spans.spans.size(), 0);
    result.lo = n;
    result.hi = glm::ivec3(0);
    for (int cz = 0; cz < n.z; ++cz)
        for (int cy = 0; cy < n.y; ++cy)
            for (int cx = 0; cx < n.x; ++cx) {
                const std::size_t i =
                    std::size_t(cx) + std::size_t(n.x) * (cy + std::size_t(n.y) * cz);
                const ValueSpan& s = spans.spans[i];
                if (s.lo > s.hi || !visible.anyIn(s.lo, s.hi)) continue;
                result.flags[i] = 1;
                result.lo = glm::min(result.lo, glm::ivec3(cx, cy, cz));
                result.hi = glm::max(result.hi, glm::ivec3(cx, cy, cz) + 1);
            }
    if (glm::any(glm::greaterThanEqual(result.lo, result.hi)))
        result.lo = result.hi = glm::ivec3(0);
    result.distance = chessboardDistance(n, result.flags);
    return result;
}

RayCells rayCells(const Volume& scan, bake::ValueWindow window, const VisibleValues& visible,
                  int marginVoxels) {
    return rayCells(spanGrid(scan, window, kRayCellVoxels, 1 + marginVoxels), visible);
}

} // namespace cutaway::render
