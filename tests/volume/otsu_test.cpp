// Otsu's threshold (used to segment the background for the distance field).
#include "volume/otsu.hpp"

#include <cstring>
#include <gtest/gtest.h>
#include <random>

namespace cutaway::test {
namespace {

Volume fromValues(const std::vector<float>& values) {
    Volume v = Volume::allocate({int(values.size()), 1, 1}, VoxelType::F32);
    std::memcpy(v.data.data(), values.data(), values.size() * sizeof(float));
    return v;
}

} // namespace

TEST(Otsu, SplitsTwoGaussiansBetweenTheirModes) {
    std::mt19937 rng(3);
    std::normal_distribution<float> air(100.0f, 10.0f), tissue(400.0f, 30.0f);
    std::vector<float> values;
    for (int i = 0; i < 30000; ++i)
        values.push_back(air(rng));
    for (int i = 0; i < 10000; ++i)
        values.push_back(tissue(rng));
    const double t = otsuThreshold(fromValues(values));
    EXPECT_GT(t, 150.0);
    EXPECT_LT(t, 320.0);
    // Moving the upper mode moves the threshold with it.
    for (float& v : values)
        if (v > t) v += 400.0f;
    EXPECT_GT(otsuThreshold(fromValues(values)), t + 50.0);
}

TEST(Otsu, TwoValuesSplitInTheMiddleAndConstantsGiveTheirValue) {
    EXPECT_NEAR(otsuThreshold(fromValues({0, 0, 0, 255, 255})), 127.5, 1.0);
    EXPECT_EQ(otsuThreshold(fromValues({7, 7, 7})), 7.0);
}

TEST(Otsu, HonoursSlopeAndIntercept) {
    Volume v = Volume::allocate({4, 1, 1}, VoxelType::U8);
    for (int i = 0; i < 4; ++i)
        v.data[std::size_t(i)] = std::byte(i < 2 ? 10 : 200);
    v.slope = 2.0;
    v.inter = -1000.0;
    const double t = otsuThreshold(v);
    EXPECT_GT(t, 2.0 * 10 - 1000.0);
    EXPECT_LT(t, 2.0 * 200 - 1000.0);
}

} // namespace cutaway::test
