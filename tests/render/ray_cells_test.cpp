// Empty-space skipping's bookkeeping, on the CPU: which values the tables the
// shaders read can show (VisibleValues) and the ray caster's cells (RayCells)
// with their distances to the nearest occupied cell.
// The claim the ray caster relies on: in a cell flagged empty, every
// trilinear sample and every slab up to the margin long that starts there is
// transparent.
#include "render/classify/preintegration.hpp"
#include "render/classify/transfer_table.hpp"
#include "render/skipping/occupancy.hpp"
#include "render/skipping/ray_cells.hpp"
#include "shared/visible_runs.h"
#include "volume/volume.hpp"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <random>

namespace cutaway::test {
namespace {

using render::kRayCellVoxels;

// Visible only in a narrow band of values, so that most of the scan is air.
TransferFunction band(double lo, double hi) {
    return {{{0.0, glm::vec3(1.0f), 0.0f},
             {lo, glm::vec3(1.0f), 0.0f},
             {0.5 * (lo + hi), glm::vec3(1.0f), 0.6f},
             {hi, glm::vec3(1.0f), 0.0f},
             {255.0, glm::vec3(1.0f), 0.0f}}};
}

constexpr bake::ValueWindow kWindow{0.0, 255.0};

// Air with a few blobs of different values and sizes, sizes not multiples of a cell.
Volume blobs() {
    Volume v = Volume::allocate({29, 23, 34}, VoxelType::U8);
    const struct {
        glm::dvec3 centre;
        double radius, value;
    } list[] = {{{6, 5, 7}, 3.0, 120}, {{20, 15, 25}, 5.0, 200}, {{14, 4, 30}, 2.0, 60}};
    for (int z = 0; z < v.dims.z; ++z)
        for (int y = 0; y < v.dims.y; ++y)
            for (int x = 0; x < v.dims.x; ++x) {
                double value = 0.0;
                for (const auto& b : list) {
                    const double d = glm::length(glm::dvec3(x, y, z) - b.centre);
                    value = std::max(value, b.value * std::clamp(b.radius + 0.5 - d, 0.0, 1.0));
                }
                v.data[v.index(x, y, z)] = std::byte(static_cast<uint8_t>(value));
            }
    return v;
}

// The normalized value the GPU samples at voxel coordinates p (voxel i's
// centre at i), trilinear with clamp to edge.
float sampleAt(const Volume& v, glm::dvec3 p) {
    p = glm::clamp(p, glm::dvec3(0.0), glm::dvec3(v.dims - 1));
    const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(p)), v.dims - 2);
    const glm::dvec3 t = p - glm::dvec3(i0);
    double sum = 0.0;
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        const glm::dvec3 w = glm::mix(1.0 - t, t, glm::dvec3(o));
        sum += w.x * w.y * w.z * v.value(i0.x + o.x, i0.y + o.y, i0.z + o.z) / 255.0;
    }
    return static_cast<float>(sum);
}

// Whether the table of n entries per axis, filtered linearly at values a and
// b (texel centres at i / (n - 1); one axis when post-classified), can give
// opacity there.
bool tableShows(const std::vector<glm::vec4>& table, int n, bool twoD, float a, float b) {
    const auto reach = [n](float v) {
        const float x = v * float(n - 1);
        const int i0 = std::min(static_cast<int>(x), n - 1);
        return std::pair<int, int>(i0, x > float(i0) ? std::min(i0 + 1, n - 1) : i0);
    };
    const auto [f0, f1] = reach(a);
    const auto [b0, b1] = twoD ? reach(b) : std::pair<int, int>(0, 0);
    for (int f : {f0, f1})
        for (int bb : {b0, b1})
            if (table[std::size_t(bb) * std::size_t(n) + std::size_t(f)].w > 0.0f) return true;
    return false;
}

TEST(VisibleValues, CoverEverySampleTheTablesShow) {
    // Samples and slabs between values a and b that the filtered table gives
    // opacity are reported visible, for both classifications. The
    // pre-integrated table resamples the function at coarser entries, so its
    // slabs reach values the function's own entries do not: checking them
    // against the function's entries misses some (the last expectation).
    const std::vector<TransferFunction> functions{band(100.0, 104.0), band(40.0, 200.0)};
    for (const TransferFunction& tf : functions) {
        const std::vector<glm::vec4> table = render::tabulateTransfer(tf, kWindow);
        const int n = render::kPreintegrationSize;
        const std::vector<glm::vec4> slabs = render::preintegrate(table, 1.0, 1.0, n);
        const render::VisibleValues post({&tf}, kWindow, false), pre({&tf}, kWindow, true);
        int missedByPost = 0;
        const int steps = 2000;
        for (int i = 0; i <= steps; ++i) {
            const float a = float(i) / float(steps);
            if (tableShows(table, render::kTransferTableSize, false, a, a)) {
                EXPECT_TRUE(post.anyIn(a, a)) << a;
            }
            for (int j = std::max(0, i - 40); j <= std::min(steps, i + 40); ++j) {
                const float b = float(j) / float(steps);
                if (!tableShows(slabs, n, true, a, b)) continue;
                EXPECT_TRUE(pre.anyIn(std::min(a, b), std::max(a, b))) << a << ", " << b;
                missedByPost += post.anyIn(std::min(a, b), std::max(a, b)) ? 0 : 1;
            }
        }
        if (&tf == &functions[0]) {
            EXPECT_GT(missedByPost, 0) << "the narrow band must need the coarser table's bins";
        }
    }
}

// Visible in `count` narrow bands of values spread over the range.
TransferFunction bands(int count) {
    TransferFunction tf{{{0.0, glm::vec3(1.0f), 0.0f}}};
    for (int i = 0; i < count; ++i) {
        const double lo = 20.0 + 220.0 * i / count;
        tf.points.push_back({lo, glm::vec3(1.0f), 0.0f});
        tf.points.push_back({lo + 3.0, glm::vec3(1.0f), 0.5f});
        tf.points.push_back({lo + 6.0, glm::vec3(1.0f), 0.0f});
    }
    tf.points.push_back({255.0, glm::vec3(1.0f), 0.0f});
    return tf;
}

TEST(VisibleValues, RunsAnswerAsTheTableDoesAndJoinedRunsOnlyAddSlabs) {
    // runsMayShow (the ray caster's test) against anyIn (the table of first
    // visible bins): the same answer for up to CW_VISIBLE_RUNS runs; with more,
    // every slab anyIn passes and some it does not (the joined gaps).
    const std::vector<std::pair<TransferFunction, int>> cases{{band(100.0, 104.0), 1},
                                                              {band(40.0, 200.0), 1},
                                                              {bands(2), 2},
                                                              {bands(4), 4},
                                                              {bands(7), 7}};
    for (const auto& [tf, expectedRuns] : cases) {
        for (const bool preintegrated : {false, true}) {
            const render::VisibleValues visible({&tf}, kWindow, preintegrated);
            const render::VisibleValues::Runs runs = visible.runs();
            int count = 0, previousEnd = -1;
            for (int r = 0; r < CW_VISIBLE_RUNS; ++r) {
                if (runs.lo[r] == runs.hi[r]) continue;
                ++count;
                EXPECT_LT(runs.lo[r], runs.hi[r]);
                EXPECT_GT(runs.lo[r], previousEnd) << "runs in order, apart";
                previousEnd = runs.hi[r];
            }
            EXPECT_EQ(count, std::min(expectedRuns, CW_VISIBLE_RUNS)) << expectedRuns;
            EXPECT_EQ(runs.bins, static_cast<int>(visible.firstFrom().size()) - 1);
            int onlyRuns = 0;
            const int steps = 1500;
            for (int i = 0; i <= steps; ++i)
                for (int j = std::max(0, i - 30); j <= std::min(steps, i + 30); j += 3) {
                    const float a = float(i) / float(steps), b = float(j) / float(steps);
                    const bool exact = visible.anyIn(std::min(a, b), std::max(a, b));
                    const bool viaRuns = shader::runsMayShow(runs.lo, runs.hi, runs.bins, a, b);
                    if (exact) {
                        EXPECT_TRUE(viaRuns) << a << ", " << b;
                    } else if (expectedRuns <= CW_VISIBLE_RUNS) {
                        EXPECT_FALSE(viaRuns) << a << ", " << b;
                    }
                    onlyRuns += viaRuns && !exact ? 1 : 0;
                }
            if (expectedRuns > CW_VISIBLE_RUNS) {
                EXPECT_GT(onlyRuns, 0) << "joined runs must cover a gap";
            }
        }
    }
}

// Whether every sample in each empty cell, and every slab from it up to
// `reach` voxels along each axis, is transparent; counts the failures.
int transparencyViolations(const Volume& v, const render::RayCells& cells,
                           const render::VisibleValues& visible, double reach) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0), offset(-reach, reach);
    int violations = 0;
    for (int cz = 0; cz < cells.cells.z; ++cz)
        for (int cy = 0; cy < cells.cells.y; ++cy)
            for (int cx = 0; cx < cells.cells.x; ++cx) {
                const glm::ivec3 c(cx, cy, cz);
                if (cells.flags[std::size_t(cx) + std::size_t(cells.cells.x) *
                                                      (cy + std::size_t(cells.cells.y) * cz)])
                    continue;
                for (int k = 0; k < 200; ++k) {
                    // A point of the cell: voxel coordinates [4c - 0.5, 4c + 3.5).
                    const glm::dvec3 p =
                        glm::dvec3(c * kRayCellVoxels) - 0.5 +
                        glm::dvec3(unit(rng), unit(rng), unit(rng)) * double(kRayCellVoxels);
                    const glm::dvec3 q = p + glm::dvec3(offset(rng), offset(rng), offset(rng));
                    const float a = sampleAt(v, p), b = sampleAt(v, q);
                    violations += visible.anyIn(std::min(a, b), std::max(a, b)) ? 1 : 0;
                }
            }
    return violations;
}

TEST(RayCells, EmptyCellsHoldOnlyTransparentSamplesAndSlabs) {
    const Volume v = blobs();
    for (const TransferFunction& tf : {band(90.0, 150.0), band(30.0, 80.0), band(150.0, 255.0)}) {
        const render::VisibleValues visible({&tf}, kWindow, true);
        for (int margin : {0, 1, 2, 3}) {
            const render::RayCells cells = render::rayCells(v, kWindow, visible, margin);
            EXPECT_EQ(transparencyViolations(v, cells, visible, margin + 0.5), 0)
                << "margin " << margin;
            // The same check sees a margin too small for the slabs.
            if (margin == 2) {
                EXPECT_GT(transparencyViolations(v, render::rayCells(v, kWindow, visible, 0),
                                                 visible, margin + 0.5),
                          0);
            }
        }
    }
}

TEST(RayCells, TheMarginCoversTheSlab) {
    // A slab of L voxels needs m + 0.5 >= L, and no more.
    for (double slab : {0.0, 0.3, 0.5, 0.51, 1.0, 1.08, 1.5, 2.2, 6.0}) {
        const int m = render::slabMargin(slab);
        EXPECT_GE(m + 0.5, slab) << slab;
        EXPECT_LT(m - 0.5, std::max(slab, 0.5)) << slab;
    }
}

TEST(RayCells, FlagEachCellByTheValuesItsSamplesRead) {
    // Against a direct computation: the range over the cell's voxels, one more
    // on each side and the margin, clamped to the volume.
    const Volume v = blobs();
    const TransferFunction tf = band(90.0, 150.0);
    const render::VisibleValues visible({&tf}, kWindow, false);
    for (int margin : {0, 2, 5}) {
        const render::RayCells cells = render::rayCells(v, kWindow, visible, margin);
        ASSERT_EQ(cells.cells, (v.dims + kRayCellVoxels - 1) / kRayCellVoxels);
        int occupied = 0;
        glm::ivec3 lo(1 << 20), hi(0);
        for (int cz = 0; cz < cells.cells.z; ++cz)
            for (int cy = 0; cy < cells.cells.y; ++cy)
                for (int cx = 0; cx < cells.cells.x; ++cx) {
                    const glm::ivec3 c(cx, cy, cz);
                    const glm::ivec3 first = glm::max(c * kRayCellVoxels - 1 - margin, 0);
                    const glm::ivec3 last =
                        glm::min(c * kRayCellVoxels + kRayCellVoxels + margin, v.dims - 1);
                    float a = 1.0f, b = 0.0f;
                    for (int z = first.z; z <= last.z; ++z)
                        for (int y = first.y; y <= last.y; ++y)
                            for (int x = first.x; x <= last.x; ++x) {
                                const float value = float(v.value(x, y, z) / 255.0);
                                a = std::min(a, value);
                                b = std::max(b, value);
                            }
                    const bool expected = visible.anyIn(a, b);
                    const bool flagged =
                        cells.flags[std::size_t(cx) + std::size_t(cells.cells.x) *
                                                          (cy + std::size_t(cells.cells.y) * cz)];
                    EXPECT_EQ(flagged, expected) << "cell " << cx << " " << cy << " " << cz;
                    if (expected) {
                        ++occupied;
                        lo = glm::min(lo, c);
                        hi = glm::max(hi, c + 1);
                    }
                }
        const int total = cells.cells.x * cells.cells.y * cells.cells.z;
        EXPECT_GT(occupied, 0);
        EXPECT_LT(occupied, margin == 0 ? total / 2 : total) << "mostly air";
        EXPECT_EQ(cells.lo, lo);
        EXPECT_EQ(cells.hi, hi);
        // Each cell's distance: the chessboard distance to the nearest occupied cell.
        const glm::ivec3 n = cells.cells;
        for (std::size_t i = 0; i < cells.flags.size(); ++i) {
            const glm::ivec3 c(int(i) % n.x, int(i) / n.x % n.y, int(i) / (n.x * n.y));
            int nearest = 255;
            for (std::size_t j = 0; j < cells.flags.size(); ++j) {
                if (!cells.flags[j]) continue;
                const glm::ivec3 d = glm::abs(
                    glm::ivec3(int(j) % n.x, int(j) / n.x % n.y, int(j) / (n.x * n.y)) - c);
                nearest = std::min(nearest, std::max(d.x, std::max(d.y, d.z)));
            }
            ASSERT_EQ(int(cells.distance[i]), nearest)
                << "cell " << c.x << " " << c.y << " " << c.z;
        }
    }
    // Nothing visible: no cell, and empty bounds.
    const TransferFunction none = band(250.0, 254.0);
    const render::RayCells empty =
        render::rayCells(v, kWindow, render::VisibleValues({&none}, kWindow, false), 2);
    EXPECT_EQ(std::count(empty.flags.begin(), empty.flags.end(), uint8_t(1)), 0);
    EXPECT_EQ(std::count(empty.distance.begin(), empty.distance.end(), uint8_t(255)),
              std::ptrdiff_t(empty.distance.size()));
    EXPECT_EQ(empty.lo, empty.hi);
}

TEST(SpanGrid, SpansKeptInStepsStillCoverTheirValues) {
    // Spans are kept in 1/255 steps, rounded outward: a span must contain the
    // values it was made of, so that a cell whose exact span may show is never
    // flagged empty; and it must be no more than a step wider on each side.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const TransferFunction narrow = band(121.3, 122.9); // visible in a bin or two
    for (bool preintegrated : {true, false}) {
        const render::VisibleValues visible({&narrow}, kWindow, preintegrated);
        int shown = 0;
        for (int i = 0; i < 20000; ++i) {
            float a = unit(rng), b = unit(rng);
            if (i % 2) b = a + 0.01f * unit(rng) * unit(rng); // many narrow spans
            if (a > b) std::swap(a, b);
            b = std::min(b, 1.0f);
            const render::ValueSpan span = render::ValueSpan::covering(a, b);
            ASSERT_FALSE(span.empty());
            ASSERT_LE(span.low(), a) << a;
            ASSERT_GE(span.high(), b) << b;
            ASSERT_GT(span.low(), a - 1.0f / 255.0f - 1e-6f) << a;
            ASSERT_LT(span.high(), b + 1.0f / 255.0f + 1e-6f) << b;
            if (visible.anyIn(a, b)) {
                ++shown;
                ASSERT_TRUE(visible.anyIn(span.low(), span.high())) << a << " " << b;
            }
        }
        EXPECT_GT(shown, 100) << "the band must be met";
    }
    EXPECT_TRUE(render::ValueSpan{}.empty());
}

TEST(SpanGrid, BricksAreTheUnionsOfTheirCells) {
    // Bricks take their spans from the ray caster's cells (one pass over the
    // scan): exact, partial last cells and clamping included.
    std::mt19937 rng(7);
    for (const glm::ivec3 dims :
         {glm::ivec3(29, 23, 34), glm::ivec3(9, 16, 5), glm::ivec3(1, 7, 8)}) {
        Volume v = Volume::allocate(dims, VoxelType::U8);
        for (std::byte& b : v.data)
            b = std::byte(static_cast<uint8_t>(rng() % 256));
        for (int extra : {1, 2, 3, 6}) {
            const render::SpanGrid direct =
                render::spanGrid(v, kWindow, render::kBrickVoxels, extra);
            const render::SpanGrid merged =
                render::brickSpans(render::spanGrid(v, kWindow, kRayCellVoxels, extra));
            ASSERT_EQ(merged.cells, direct.cells);
            ASSERT_EQ(merged.cellVoxels, render::kBrickVoxels);
            ASSERT_EQ(merged.spans.size(), direct.spans.size());
            for (std::size_t i = 0; i < direct.spans.size(); ++i) {
                EXPECT_EQ(merged.spans[i].lo, direct.spans[i].lo) << i << " extra " << extra;
                EXPECT_EQ(merged.spans[i].hi, direct.spans[i].hi) << i << " extra " << extra;
            }
        }
    }
}

TEST(RayCells, DistancesAreChessboardDistancesToTheNearestOccupiedCell) {
    // Cells flagged by hand (a visible span or an invisible one), sparse and in
    // lines, against the definition; far from every occupied cell it saturates.
    const TransferFunction tf = band(90.0, 150.0);
    const render::VisibleValues visible({&tf}, kWindow, false);
    const render::ValueSpan shows = render::ValueSpan::covering(120.0f / 255.0f, 120.0f / 255.0f),
                            clear = render::ValueSpan::covering(0.0f, 0.0f);
    std::mt19937 rng(11);
    const glm::ivec3 n(37, 21, 300);
    for (int layout = 0; layout < 3; ++layout) {
        render::SpanGrid grid{n, kRayCellVoxels,
                              std::vector<render::ValueSpan>(std::size_t(n.x) * n.y * n.z, clear)};
        const auto index = [&](glm::ivec3 c) {
            return std::size_t(c.x) + std::size_t(n.x) * (c.y + std::size_t(n.y) * c.z);
        };
        if (layout == 0)
            for (int i = 0; i < 6; ++i)
                grid.spans[index({int(rng() % n.x), int(rng() % n.y), int(rng() % 40)})] = shows;
        if (layout == 1)
            for (int x = 3; x < n.x; ++x)
                grid.spans[index({x, n.y - 1 - x % n.y, 17})] = shows;
        if (layout == 2) grid.spans[index({n.x - 1, 0, 0})] = shows;
        const render::RayCells cells = render::rayCells(grid, visible);
        std::vector<glm::ivec3> occupied;
        for (std::size_t i = 0; i < grid.spans.size(); ++i)
            if (cells.flags[i])
                occupied.push_back({int(i) % n.x, int(i) / n.x % n.y, int(i) / (n.x * n.y)});
        ASSERT_FALSE(occupied.empty());
        int far = 0;
        for (std::size_t i = 0; i < grid.spans.size(); ++i) {
            const glm::ivec3 c(int(i) % n.x, int(i) / n.x % n.y, int(i) / (n.x * n.y));
            int nearest = 255;
            for (const glm::ivec3 o : occupied) {
                const glm::ivec3 d = glm::abs(o - c);
                nearest = std::min(nearest, std::max(d.x, std::max(d.y, d.z)));
            }
            far += nearest == 255 ? 1 : 0;
            ASSERT_EQ(int(cells.distance[i]), nearest)
                << "layout " << layout << " cell " << c.x << " " << c.y << " " << c.z;
        }
        EXPECT_GT(far, 0) << "the grid reaches past 255 cells from every occupied one";
    }
}

} // namespace
} // namespace cutaway::test
