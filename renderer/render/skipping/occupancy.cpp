#include "render/skipping/occupancy.hpp"

#include "render/classify/preintegration.hpp"
#include "render/classify/transfer_table.hpp"
#include "shared/visible_runs.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace cutaway::render {

static_assert(kSpanSteps == kPreintegrationSize - 1, "the spans' steps are the tables' bins");

namespace {

// The summed-area table of occ.flags.
void fillSums(BrickOccupancy& occ) {
    const glm::ivec3 n = occ.bricks + 1;
    occ.sums.assign(std::size_t(n.x) * n.y * n.z, 0);
    const auto s = [&](int x, int y, int z) -> uint32_t& {
        return occ.sums[std::size_t(x) + std::size_t(n.x) * (y + std::size_t(n.y) * z)];
    };
    for (int z = 1; z < n.z; ++z)
        for (int y = 1; y < n.y; ++y)
            for (int x = 1; x < n.x; ++x) {
                const uint32_t f = occ.flags[std::size_t(x - 1) +
                                             std::size_t(occ.bricks.x) *
                                                 (y - 1 + std::size_t(occ.bricks.y) * (z - 1))];
                s(x, y, z) = f + s(x - 1, y, z) + s(x, y - 1, z) + s(x, y, z - 1) -
                             s(x - 1, y - 1, z) - s(x - 1, y, z - 1) - s(x, y - 1, z - 1) +
                             s(x - 1, y - 1, z - 1);
            }
}

} // namespace

SpanGrid spanGrid(const Volume& scan, bake::ValueWindow window, int cellVoxels, int extra) {
    const int k = cellVoxels;
    const glm::ivec3 n = (scan.dims + (k - 1)) / k;
    // The range over a cell's reach is separable: each row's values reduced
    // over the cells' reach along x, those rows over the reach along y, the
    // slices over z. Every voxel falls in the reach of a few cells at most.
    std::vector<ValueSpan> grid(std::size_t(n.x) * n.y * n.z), slice(std::size_t(n.x) * n.y);
    std::vector<float> row(std::size_t(scan.dims.x));
    std::vector<ValueSpan> rowSpans(std::size_t(n.x));
    const double scale = 1.0 / (window.hi - window.lo);
    // The cells whose reach includes voxel i: from floor((i - extra) / k) to
    // floor((i + extra) / k) (the first rounded down below zero, then clamped).
    const auto cellsOf = [&](int i, int cells) {
        const int shift = extra + 1; // keeps the division's operand positive
        const int lo = (i - extra + shift * k) / k - shift;
        return std::pair<int, int>(std::max(lo, 0), std::min(cells - 1, (i + extra) / k));
    };
    for (int z = 0; z < scan.dims.z; ++z) {
        std::fill(slice.begin(), slice.end(), ValueSpan{});
        for (int y = 0; y < scan.dims.y; ++y) {
            const std::size_t base = scan.index(0, y, z);
            for (int x = 0; x < scan.dims.x; ++x)
                row[std::size_t(x)] = static_cast<float>(
                    std::clamp((scan.value(base + std::size_t(x)) - window.lo) * scale, 0.0, 1.0));
            for (int cx = 0; cx < n.x; ++cx) {
                const int first = std::max(cx * k - extra, 0);
                const int last = std::min(cx * k + k - 1 + extra, scan.dims.x - 1);
                float lo = row[std::size_t(first)], hi = lo;
                for (int x = first + 1; x <= last; ++x) {
                    lo = std::min(lo, row[std::size_t(x)]);
                    hi = std::max(hi, row[std::size_t(x)]);
                }
                rowSpans[std::size_t(cx)] = ValueSpan::covering(lo, hi);
            }
            const auto [cy0, cy1] = cellsOf(y, n.y);
            for (int cy = cy0; cy <= cy1; ++cy)
                for (int cx = 0; cx < n.x; ++cx)
                    slice[std::size_t(cx) + std::size_t(n.x) * std::size_t(cy)].add(
                        rowSpans[std::size_t(cx)]);
        }
        const auto [cz0, cz1] = cellsOf(z, n.z);
        for (int cz = cz0; cz <= cz1; ++cz)
            for (std::size_t i = 0; i < slice.size(); ++i)
                grid[i + slice.size() * std::size_t(cz)].add(slice[i]);
    }
    return {n, k, std::move(grid)};
}

SpanGrid coarsened(const SpanGrid& fine) {
    SpanGrid coarse{(fine.cells + 1) / 2, 2 * fine.cellVoxels, {}};
    const glm::ivec3 n = coarse.cells;
    coarse.spans.resize(std::size_t(n.x) * n.y * n.z);
    for (int z = 0; z < fine.cells.z; ++z)
        for (int y = 0; y < fine.cells.y; ++y)
            for (int x = 0; x < fine.cells.x; ++x)
                coarse
                    .spans[std::size_t(x / 2) +
                           std::size_t(n.x) * (y / 2 + std::size_t(n.y) * (z / 2))]
                    .add(fine.spans[std::size_t(x) + std::size_t(fine.cells.x) *
                                                         (y + std::size_t(fine.cells.y) * z)]);
    return coarse;
}

int slabMargin(double slabVoxels) {
    return std::max(0, static_cast<int>(std::ceil(slabVoxels - 0.5)));
}

VisibleValues::VisibleValues(const std::vector<const TransferFunction*>& transfers,
                             bake::ValueWindow window, bool preintegrated) {
    std::vector<bool> visible(kTransferTableSize, false);
    for (const TransferFunction* tf : transfers) {
        const std::vector<glm::vec4> table = tabulateTransfer(*tf, window);
        for (int i = 0; i < kTransferTableSize; ++i)
            visible[i] = visible[i] || table[i].w > 0.0f;
    }
    if (preintegrated) {
        // preintegrate() takes entry i of its n from the function at
        // (size - 1) * i / (n - 1), between two of its entries.
        std::vector<bool> coarse(kPreintegrationSize, false);
        for (int i = 0; i < kPreintegrationSize; ++i) {
            const int at = (kTransferTableSize - 1) * i / (kPreintegrationSize - 1);
            coarse[i] = visible[at] || visible[std::min(at + 1, kTransferTableSize - 1)];
        }
        visible = std::move(coarse);
    }
    const int bins = static_cast<int>(visible.size());
    m_firstFrom.assign(visible.size() + 1, bins);
    for (int i = bins - 1; i >= 0; --i)
        m_firstFrom[std::size_t(i)] = visible[std::size_t(i)] ? i : m_firstFrom[std::size_t(i) + 1];
}

bool VisibleValues::anyIn(float lo, float hi) const {
    const float last = static_cast<float>(m_firstFrom.size() - 2);
    const int first = std::clamp(static_cast<int>(std::floor(lo * last)), 0, int(last));
    const int end = std::clamp(static_cast<int>(std::ceil(hi * last)), 0, int(last)) + 1;
    return m_firstFrom[std::size_t(first)] < end;
}

VisibleValues::Runs VisibleValues::runs() const {
    const int bins = static_cast<int>(m_firstFrom.size()) - 1;
    std::vector<glm::ivec2> runs; // [lo, hi) of each run of visible bins, in order
    for (int i = m_firstFrom[0]; i < bins;) {
        int end = i;
        while (end < bins && m_firstFrom[std::size_t(end)] == end)
            ++end;
        runs.push_back({i, end});
        i = m_firstFrom[std::size_t(end)];
    }
    while (runs.size() > CW_VISIBLE_RUNS) { // join the two runs with the narrowest gap
        std::size_t narrowest = 0;
        for (std::size_t r = 1; r + 1 < runs.size(); ++r)
            if (runs[r + 1].x - runs[r].y < runs[narrowest + 1].x - runs[narrowest].y)
                narrowest = r;
        runs[narrowest].y = runs[narrowest + 1].y;
        runs.erase(runs.begin() + std::ptrdiff_t(narrowest) + 1);
    }
    Runs result{glm::ivec4(0), glm::ivec4(0), bins, 0, 0, 0};
    for (std::size_t r = 0; r < runs.size(); ++r) {
        result.lo[int(r)] = runs[r].x;
        result.hi[int(r)] = runs[r].y;
    }
    return result;
}

BrickOccupancy brickOccupancy(const SpanGrid& bricks, const Box& box, glm::dvec3 spacing,
                              const VisibleValues& visible) {
    BrickOccupancy occ;
    occ.bricks = bricks.cells;
    occ.box = box;
    occ.brickMm = double(bricks.cellVoxels) * spacing;
    occ.flags.resize(bricks.spans.size());
    std::transform(bricks.spans.begin(), bricks.spans.end(), occ.flags.begin(),
                   [&](const ValueSpan& r) {
                       return uint8_t(!r.empty() && visible.anyIn(r.low(), r.high()) ? 1 : 0);
                   });
    fillSums(occ);
    return occ;
}

BrickOccupancy brickOccupancy(const Volume& scan, const Box& box, bake::ValueWindow window,
                              const VisibleValues& visible, int marginVoxels) {
    return brickOccupancy(spanGrid(scan, window, kBrickVoxels, 1 + marginVoxels), box, scan.spacing,
                          visible);
}

BrickOccupancy fullOccupancy(const Box& box) {
    BrickOccupancy occ;
    occ.bricks = glm::ivec3(1);
    occ.box = box;
    occ.brickMm = box.hi - box.lo;
    occ.flags = {1};
    fillSums(occ);
    return occ;
}

bool BrickOccupancy::anyIn(glm::dvec3 lo, glm::dvec3 hi) const {
    if (glm::any(glm::greaterThan(lo, box.hi)) || glm::any(glm::lessThan(hi, box.lo))) return false;
    const glm::ivec3 last = bricks - 1;
    const glm::ivec3 a =
        glm::clamp(glm::ivec3(glm::floor((lo - box.lo) / brickMm)), glm::ivec3(0), last);
    const glm::ivec3 b =
        glm::clamp(glm::ivec3(glm::floor((hi - box.lo) / brickMm)), glm::ivec3(0), last) + 1;
    const glm::ivec3 n = bricks + 1;
    const auto s = [&](int x, int y, int z) {
        return int64_t(sums[std::size_t(x) + std::size_t(n.x) * (y + std::size_t(n.y) * z)]);
    };
    const int64_t count = s(b.x, b.y, b.z) - s(a.x, b.y, b.z) - s(b.x, a.y, b.z) -
                          s(b.x, b.y, a.z) + s(a.x, a.y, b.z) + s(a.x, b.y, a.z) +
                          s(b.x, a.y, a.z) - s(a.x, a.y, a.z);
    return count > 0;
}

std::vector<CellRun> mergeCells(glm::ivec3 dims, const std::vector<uint8_t>& flags) {
    const auto at = [&](int x, int y, int z) {
        return std::size_t(x) + std::size_t(dims.x) * (y + std::size_t(dims.y) * z);
    };
    // Runs along x, then equal runs of consecutive rows merged along y.
    std::vector<CellRun> open, done;
    for (int z = 0; z < dims.z; ++z) {
        for (int y = 0; y < dims.y; ++y) {
            std::vector<CellRun> next;
            for (int x = 0; x < dims.x;) {
                if (!flags[at(x, y, z)]) {
                    ++x;
                    continue;
                }
                const int x0 = x;
                while (x < dims.x && flags[at(x, y, z)])
                    ++x;
                auto same = std::find_if(open.begin(), open.end(), [&](const CellRun& r) {
                    return r.lo.x == x0 && r.hi.x == x && r.hi.y == y;
                });
                if (same != open.end()) {
                    CellRun grown = *same;
                    grown.hi.y = y + 1;
                    open.erase(same);
                    next.push_back(grown);
                } else {
                    next.push_back({{x0, y, z}, {x, y + 1, z + 1}});
                }
            }
            done.insert(done.end(), open.begin(), open.end());
            open = std::move(next);
        }
        done.insert(done.end(), open.begin(), open.end());
        open.clear();
    }
    // Boxes with the same rectangle in consecutive layers become one: fewer,
    // larger polygons per slice (thin ones waste a rasterizer's SIMD lanes).
    std::sort(done.begin(), done.end(), [](const CellRun& a, const CellRun& b) {
        return std::tie(a.lo.x, a.lo.y, a.hi.x, a.hi.y, a.lo.z) <
               std::tie(b.lo.x, b.lo.y, b.hi.x, b.hi.y, b.lo.z);
    });
    std::vector<CellRun> merged;
    for (const CellRun& r : done) {
        if (!merged.empty()) {
            CellRun& m = merged.back();
            if (m.lo.x == r.lo.x && m.lo.y == r.lo.y && m.hi.x == r.hi.x && m.hi.y == r.hi.y &&
                m.hi.z == r.lo.z) {
                m.hi.z = r.hi.z;
                continue;
            }
        }
        merged.push_back(r);
    }
    return merged;
}

std::vector<Box> BrickOccupancy::boxes() const {
    std::vector<Box> result;
    for (const CellRun& r : mergeCells(bricks, flags)) {
        const glm::dvec3 lo = box.lo + glm::dvec3(r.lo) * brickMm;
        const glm::dvec3 hi = box.lo + glm::dvec3(r.hi) * brickMm;
        result.push_back({lo, glm::min(hi, box.hi)});
    }
    return result;
}

} // namespace cutaway::render
