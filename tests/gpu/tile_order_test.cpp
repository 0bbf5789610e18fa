// The ray caster's order of tile rows and of pixels in a tile
// (shared/tile_order.h): permutations, so every pixel is rendered once; lanes
// in lock-step get compact blocks; and under the rows' order each thread's contiguous
// share of the workgroups (lavapipe splits a dispatch so) covers every part of
// the image alike. In image order the first of two threads would take the top
// half: its share of the image's top quarter would be 1/2 instead of 1/4.
#include "shared/tile_order.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace cutaway::test {
namespace {

using shader::tileRowOf;
using shader::tileRowStride;

TEST(TileOrder, IsAPermutationOfTheRows) {
    for (std::uint32_t rows = 1; rows <= 2048; ++rows) {
        const std::uint32_t stride = tileRowStride(rows);
        std::vector<int> seen(rows, 0);
        for (std::uint32_t g = 0; g < rows; ++g) {
            const std::uint32_t row = tileRowOf(g, rows, stride);
            ASSERT_LT(row, rows) << rows << " rows";
            ++seen[row];
        }
        EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }))
            << rows << " rows, stride " << stride;
    }
}

// The largest difference, over threads and image quarters, between the share
// of a thread's tile rows in a quarter and 1/4, for `threads` threads each
// taking a contiguous run of rows / threads workgroup rows.
double worstQuarterShare(std::uint32_t rows, std::uint32_t threads) {
    const std::uint32_t stride = tileRowStride(rows), share = rows / threads;
    double worst = 0.0;
    for (std::uint32_t t = 0; t < threads; ++t) {
        int inQuarter[4] = {0, 0, 0, 0};
        for (std::uint32_t g = t * share; g < (t + 1) * share; ++g)
            ++inQuarter[4 * tileRowOf(g, rows, stride) / rows];
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
        EXPECT_LT(worstQuarterShare(rows, 2), 0.08) << rows << " rows, 2 threads";
        EXPECT_LT(worstQuarterShare(rows, 4), 0.19) << rows << " rows, 4 threads";
    }
    EXPECT_LT(worstQuarterShare(64, 2), 0.04) << "512x512, 2 threads";
}

} // namespace
} // namespace cutaway::test
