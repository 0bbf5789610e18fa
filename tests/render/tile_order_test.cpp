// The ray caster's order of tiles and of pixels in a tile
// (shared/tile_order.h): permutations, so every pixel is rendered once; lanes
// in lock-step get compact blocks; under the bands' order each thread's
// contiguous share of the workgroups (lavapipe splits a dispatch so) covers
// every part of the image alike (in image order the first of two threads
// would take the top half: its share of the image's top quarter would be 1/2
// instead of 1/4); and a tile's neighbour below in its band is marched soon
// after it.
#include "shared/tile_order.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace cutaway::test {
namespace {

using shader::spreadOrder;
using shader::spreadStride;
using shader::tileBandStride;
using shader::tileOf;

TEST(TileOrder, SpreadOrderIsAPermutation) {
    for (std::uint32_t count = 1; count <= 2048; ++count) {
        const std::uint32_t stride = spreadStride(count);
        std::vector<int> seen(count, 0);
        for (std::uint32_t g = 0; g < count; ++g) {
            const std::uint32_t item = spreadOrder(g, count, stride);
            ASSERT_LT(item, count) << count;
            ++seen[item];
        }
        EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }))
            << count << " items, stride " << stride;
    }
}

TEST(TileOrder, EveryTileOnceAndNeighboursInABandTogether) {
    for (std::uint32_t rows = 1; rows <= 70; ++rows)
        for (std::uint32_t columns : {1u, 3u, 8u, 13u}) {
            const glm::uvec2 groups(columns, rows);
            const std::uint32_t stride = tileBandStride(rows);
            std::vector<int> seen(columns * rows, 0);
            std::vector<std::uint32_t> when(columns * rows, 0);
            for (std::uint32_t y = 0; y < rows; ++y)
                for (std::uint32_t x = 0; x < columns; ++x) {
                    const glm::uvec2 t = tileOf(glm::uvec2(x, y), groups, stride);
                    ASSERT_TRUE(t.x < columns && t.y < rows) << columns << "x" << rows;
                    ++seen[t.y * columns + t.x];
                    when[t.y * columns + t.x] = y * columns + x;
                }
            ASSERT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }))
                << columns << "x" << rows << ": every tile exactly once";
            // In rows, the tile below comes a whole row of workgroups later.
            for (std::uint32_t y = 0; y + 1 < rows; ++y)
                for (std::uint32_t x = 0; x < columns; ++x)
                    if ((y + 1) % shader::kTileBand != 0) {
                        const std::int64_t gap = std::int64_t(when[(y + 1) * columns + x]) -
                                                 std::int64_t(when[y * columns + x]);
                        EXPECT_EQ(gap, 1) << columns << "x" << rows << ", tile " << x << " " << y;
                    }
        }
}

// The largest difference, over threads and image quarters, between the share
// of a thread's tiles in a quarter and 1/4, for `threads` threads each
// taking a contiguous Nth of the workgroups (x fastest), `columns` a row.
double worstQuarterShare(std::uint32_t rows, std::uint32_t threads, std::uint32_t columns) {
    const glm::uvec2 groups(columns, rows);
    const std::uint32_t stride = tileBandStride(rows), share = columns * rows / threads;
    double worst = 0.0;
    for (std::uint32_t t = 0; t < threads; ++t) {
        int inQuarter[4] = {0, 0, 0, 0};
        for (std::uint32_t g = t * share; g < (t + 1) * share; ++g)
            ++inQuarter[4 * tileOf(glm::uvec2(g % columns, g / columns), groups, stride).y / rows];
        for (int n : inQuarter)
            worst = std::max(worst, std::abs(double(n) / share - 0.25));
    }
    return worst;
}

TEST(TileOrder, EachRowOfInvocationsTakesA4x2BlockOfTheTile) {
    int seen[8][8] = {};
    for (std::uint32_t y = 0; y < 8; ++y) {
        glm::uvec2 lo(8), hi(0);
        for (std::uint32_t x = 0; x < 8; ++x) {
            const glm::uvec2 p = shader::pixelInTile(glm::uvec2(x, y));
            ASSERT_TRUE(p.x < 8 && p.y < 8) << x << " " << y;
            ++seen[p.y][p.x];
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        EXPECT_EQ(hi - lo, glm::uvec2(3, 1)) << "invocation row " << y;
    }
    for (const auto& row : seen)
        for (int n : row)
            EXPECT_EQ(n, 1) << "every pixel of the tile exactly once";
}

TEST(TileOrder, SpreadsEachThreadsShareOverTheImage) {
    for (std::uint32_t rows = 64; rows <= 2048; ++rows) { // images 512 pixels high or more
        EXPECT_LT(worstQuarterShare(rows, 2, 8), 0.09) << rows << " rows, 2 threads";
        EXPECT_LT(worstQuarterShare(rows, 4, 8), 0.19) << rows << " rows, 4 threads";
    }
    EXPECT_LT(worstQuarterShare(64, 2, 64), 0.07) << "512x512, 2 threads";
}

} // namespace
} // namespace cutaway::test
