#include "render/ray_cells.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cutaway::render {
namespace {

struct Range {
    float lo = std::numeric_limits<float>::max();
    float hi = std::numeric_limits<float>::lowest();
    void add(const Range& r) {
        lo = std::min(lo, r.lo);
        hi = std::max(hi, r.hi);
    }
};

// The voxels [first, last] along one axis that cell c reads: its own, one on
// each side for trilinear filtering and the margin, clamped to the volume.
struct Reach {
    int cellVoxels, extra, voxels;
    int first(int c) const { return std::max(c * cellVoxels - extra, 0); }
    int last(int c) const { return std::min(c * cellVoxels + cellVoxels - 1 + extra, voxels - 1); }
};

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
                        uint8_t& at =
                            distance[std::size_t(q.x) + std::size_t(n.x) * (q.y + std::size_t(n.y) * q.z)];
                        if (at != kFar) continue;
                        at = uint8_t(d);
                        next.push_back(q);
                    }
        front = std::move(next);
    }
    return distance;
}

} // namespace

int rayCellMargin(double slabVoxels) {
    return std::max(0, static_cast<int>(std::ceil(slabVoxels - 0.5)));
}

RayCells rayCells(const Volume& scan, bake::ValueWindow window, const VisibleValues& visible,
                  int marginVoxels) {
    RayCells result;
    result.marginVoxels = marginVoxels;
    const glm::ivec3 n = (scan.dims + (kRayCellVoxels - 1)) / kRayCellVoxels;
    result.cells = n;
    const int extra = 1 + marginVoxels;
    const Reach rx{kRayCellVoxels, extra, scan.dims.x};

    // The range over a cell's reach is separable: each row's values reduced
    // over the cells' reach along x, those rows over the reach along y, the
    // slices over z. Every voxel falls in the reach of at most a few cells.
    std::vector<Range> grid(std::size_t(n.x) * n.y * n.z), slice(std::size_t(n.x) * n.y);
    std::vector<float> row(std::size_t(scan.dims.x));
    std::vector<Range> rowRanges(std::size_t(n.x));
    const double scale = 1.0 / (window.hi - window.lo);
    // The cells whose reach includes voxel i: from floor((i - extra) / k) to
    // floor((i + extra) / k) (the first rounded down below zero, then clamped).
    const auto cellsOf = [&](int i, int cells) {
        const int shift = extra + 1; // keeps the division's operand positive
        const int lo = (i - extra + shift * kRayCellVoxels) / kRayCellVoxels - shift;
        return std::pair<int, int>(std::max(lo, 0),
                                   std::min(cells - 1, (i + extra) / kRayCellVoxels));
    };
    for (int z = 0; z < scan.dims.z; ++z) {
        std::fill(slice.begin(), slice.end(), Range{});
        for (int y = 0; y < scan.dims.y; ++y) {
            const std::size_t base = scan.index(0, y, z);
            for (int x = 0; x < scan.dims.x; ++x)
                row[std::size_t(x)] = static_cast<float>(
                    std::clamp((scan.value(base + std::size_t(x)) - window.lo) * scale, 0.0, 1.0));
            for (int cx = 0; cx < n.x; ++cx) {
                Range r;
                for (int x = rx.first(cx); x <= rx.last(cx); ++x)
                    r.add({row[std::size_t(x)], row[std::size_t(x)]});
                rowRanges[std::size_t(cx)] = r;
            }
            const auto [cy0, cy1] = cellsOf(y, n.y);
            for (int cy = cy0; cy <= cy1; ++cy)
                for (int cx = 0; cx < n.x; ++cx)
                    slice[std::size_t(cx) + std::size_t(n.x) * cy].add(rowRanges[std::size_t(cx)]);
        }
        const auto [cz0, cz1] = cellsOf(z, n.z);
        for (int cz = cz0; cz <= cz1; ++cz)
            for (std::size_t i = 0; i < slice.size(); ++i)
                grid[i + slice.size() * std::size_t(cz)].add(slice[i]);
    }

    result.flags.assign(grid.size(), 0);
    result.lo = n;
    result.hi = glm::ivec3(0);
    for (int cz = 0; cz < n.z; ++cz)
        for (int cy = 0; cy < n.y; ++cy)
            for (int cx = 0; cx < n.x; ++cx) {
                const std::size_t i = std::size_t(cx) + std::size_t(n.x) * (cy + std::size_t(n.y) * cz);
                if (!visible.anyIn(grid[i].lo, grid[i].hi)) continue;
                result.flags[i] = 1;
                result.lo = glm::min(result.lo, glm::ivec3(cx, cy, cz));
                result.hi = glm::max(result.hi, glm::ivec3(cx, cy, cz) + 1);
            }
    if (glm::any(glm::greaterThanEqual(result.lo, result.hi))) result.lo = result.hi = glm::ivec3(0);
    result.distance = chessboardDistance(n, result.flags);
    return result;
}

} // namespace cutaway::render
