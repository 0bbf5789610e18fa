// The sampling offsets of shaders/shared/sampling.h, on the CPU twin of
// the shaders' code: off, the planes; passes, evenly spread; jittered, a
// pixel's own offset, repeatable, spread finely over any 4x4 window.
#include "shared/sampling.h"

#include <gtest/gtest.h>
#include <set>

namespace cutaway::test {
namespace {

TEST(SamplingOffsets, SpreadOverTheSpacingAndRepeat) {
    using shader::sampleOffset;
    using shader::vec2;
    using shader::vec4;
    // Off: the planes themselves; passes: evenly spread.
    EXPECT_EQ(sampleOffset(vec2(3.5f, 7.5f), vec4(0.0f, 0.0f, 0.0f, 0.0f)), 0.0f);
    EXPECT_EQ(sampleOffset(vec2(3.5f, 7.5f), vec4(0.0f, 0.25f, 0.0f, 0.0f)), 0.25f);
    // On: every offset in [0, 1), the same for the same pixel and seed, and
    // the 4x4 window's offsets spread over the spacing (at least 12 of 16
    // sixteenths hit): the noise is fine, not a few levels.
    std::set<int> bins;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const vec2 p(float(x) + 0.5f, float(y) + 0.5f);
            const float o = sampleOffset(p, vec4(1.0f, 0.0f, 7.0f, 0.0f));
            ASSERT_GE(o, 0.0f);
            ASSERT_LT(o, 1.0f);
            EXPECT_EQ(o, sampleOffset(p, vec4(1.0f, 0.0f, 7.0f, 0.0f)));
            bins.insert(int(o * 16.0f));
        }
    EXPECT_GE(bins.size(), 12u);
    // Another seed moves the pixel's offset.
    EXPECT_NE(sampleOffset(vec2(3.5f, 7.5f), vec4(1.0f, 0.0f, 7.0f, 0.0f)),
              sampleOffset(vec2(3.5f, 7.5f), vec4(1.0f, 0.0f, 8.0f, 0.0f)));
}

} // namespace
} // namespace cutaway::test
