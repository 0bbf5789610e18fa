#include "render/occupancy.hpp"

#include "render/transfer_table.hpp"

#include <algorithm>

namespace cutaway::render {
namespace {

struct Range {
    float lo = 1.0f, hi = 0.0f; // empty until a value arrives
};

// Each brick's value range, normalized over the window and clamped to [0, 1].
std::vector<Range> brickRanges(const Volume& scan, glm::ivec3 bricks, bake::ValueWindow window) {
    std::vector<Range> ranges(std::size_t(bricks.x) * bricks.y * bricks.z);
    const double scale = 1.0 / (window.hi - window.lo);
    for (int z = 0; z < scan.dims.z; ++z) {
        for (int y = 0; y < scan.dims.y; ++y) {
            Range* row = &ranges[std::size_t(bricks.x) *
                                 (y / kBrickVoxels + std::size_t(bricks.y) * (z / kBrickVoxels))];
            std::size_t i = scan.index(0, y, z);
            for (int x = 0; x < scan.dims.x; ++x, ++i) {
                const float v =
                    static_cast<float>(std::clamp((scan.value(i) - window.lo) * scale, 0.0, 1.0));
                Range& r = row[x / kBrickVoxels];
                r.lo = std::min(r.lo, v);
                r.hi = std::max(r.hi, v);
            }
        }
    }
    return ranges;
}

} // namespace

std::vector<Box> occupiedBoxes(const Volume& scan, const Box& box, bake::ValueWindow window,
                               const std::vector<const TransferFunction*>& transfers) {
    const glm::ivec3 bricks = (scan.dims + (kBrickVoxels - 1)) / kBrickVoxels;
    const std::vector<Range> ranges = brickRanges(scan, bricks, window);
    // visibleUpTo[i]: how many table entries in [0, i) have opacity, for any function.
    std::vector<int> visibleUpTo(kTransferTableSize + 1, 0);
    {
        std::vector<bool> visible(kTransferTableSize, false);
        for (const TransferFunction* tf : transfers) {
            const std::vector<glm::vec4> table = tabulateTransfer(*tf, window);
            for (int i = 0; i < kTransferTableSize; ++i)
                visible[i] = visible[i] || table[i].w > 0.0f;
        }
        for (int i = 0; i < kTransferTableSize; ++i)
            visibleUpTo[i + 1] = visibleUpTo[i] + visible[i];
    }
    const auto at = [&](int x, int y, int z) {
        return std::size_t(x) + std::size_t(bricks.x) * (y + std::size_t(bricks.y) * z);
    };
    std::vector<std::uint8_t> occupied(ranges.size(), 0);
    const float last = float(kTransferTableSize - 1);
    for (int z = 0; z < bricks.z; ++z)
        for (int y = 0; y < bricks.y; ++y)
            for (int x = 0; x < bricks.x; ++x) {
                Range r;
                for (int dz = std::max(z - 1, 0); dz <= std::min(z + 1, bricks.z - 1); ++dz)
                    for (int dy = std::max(y - 1, 0); dy <= std::min(y + 1, bricks.y - 1); ++dy)
                        for (int dx = std::max(x - 1, 0); dx <= std::min(x + 1, bricks.x - 1);
                             ++dx) {
                            const Range& n = ranges[at(dx, dy, dz)];
                            r.lo = std::min(r.lo, n.lo);
                            r.hi = std::max(r.hi, n.hi);
                        }
                if (r.lo > r.hi) continue;
                const int first = static_cast<int>(std::floor(r.lo * last));
                const int end = static_cast<int>(std::ceil(r.hi * last)) + 1;
                occupied[at(x, y, z)] = visibleUpTo[end] > visibleUpTo[first];
            }

    // Runs along x, then equal runs of consecutive rows merged along y.
    struct Run {
        int x0, x1, y0, y1, z;
    };
    std::vector<Run> open, done;
    for (int z = 0; z < bricks.z; ++z) {
        for (int y = 0; y < bricks.y; ++y) {
            std::vector<Run> next;
            for (int x = 0; x < bricks.x;) {
                if (!occupied[at(x, y, z)]) {
                    ++x;
                    continue;
                }
                const int x0 = x;
                while (x < bricks.x && occupied[at(x, y, z)])
                    ++x;
                auto same = std::find_if(open.begin(), open.end(), [&](const Run& r) {
                    return r.x0 == x0 && r.x1 == x && r.y1 == y && r.z == z;
                });
                if (same != open.end()) {
                    Run grown = *same;
                    grown.y1 = y + 1;
                    open.erase(same);
                    next.push_back(grown);
                } else {
                    next.push_back({x0, x, y, y + 1, z});
                }
            }
            done.insert(done.end(), open.begin(), open.end());
            open = std::move(next);
        }
        done.insert(done.end(), open.begin(), open.end());
        open.clear();
    }
    std::vector<Box> boxes;
    const glm::dvec3 brick = double(kBrickVoxels) * scan.spacing;
    for (const Run& r : done) {
        const glm::dvec3 lo = box.lo + glm::dvec3(r.x0, r.y0, r.z) * brick;
        const glm::dvec3 hi = box.lo + glm::dvec3(r.x1, r.y1, r.z + 1) * brick;
        boxes.push_back({lo, glm::min(hi, box.hi)});
    }
    return boxes;
}

} // namespace cutaway::render
