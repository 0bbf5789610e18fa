// Floats to halves for EXR output: the vector path gives exactly what the
// scalar one (Imath's rounding of the clamped value) gives, for every half,
// the ties between neighbouring halves, the range's ends and NaN.
#include "io/halves.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>
#include <limits>
#include <vector>

namespace cutaway::test {
namespace {

float fromBits(std::uint32_t bits) {
    return std::bit_cast<float>(bits);
}

// Every value through toHalves at once and through toHalf one by one; the
// count of those that differ, printing the first few.
int differences(const std::vector<float>& values) {
    std::vector<half> out(values.size());
    toHalves(values.data(), out.data(), values.size());
    int differ = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (out[i].bits() == toHalf(values[i]).bits()) continue;
        if (++differ <= 5)
            ADD_FAILURE() << "value " << values[i] << " (bits "
                          << std::bit_cast<std::uint32_t>(values[i]) << "): " << out[i].bits()
                          << " against " << toHalf(values[i]).bits();
    }
    return differ;
}

} // namespace

TEST(Halves, ScalarSaturatesAndTurnsNaNToZero) {
    EXPECT_EQ(toHalf(std::numeric_limits<float>::infinity()), half(65504.0f));
    EXPECT_EQ(toHalf(-std::numeric_limits<float>::infinity()), half(-65504.0f));
    EXPECT_EQ(toHalf(1e9f), half(65504.0f));
    EXPECT_EQ(toHalf(std::numeric_limits<float>::quiet_NaN()).bits(), 0);
    EXPECT_EQ(toHalf(-std::numeric_limits<float>::quiet_NaN()).bits(), 0);
    EXPECT_EQ(toHalf(0.5f), half(0.5f));
    EXPECT_EQ(toHalf(-0.0f).bits(), 0x8000);
    // A tie rounds to the even neighbour: 1 + 2^-11 lies between 1 and 1 + 2^-10.
    EXPECT_EQ(toHalf(1.0f + std::ldexp(1.0f, -11)), half(1.0f));
}

TEST(Halves, ManyAtOnceMatchOneByOneForEveryHalfAndTheTiesBetween) {
    std::vector<float> values;
    for (std::uint32_t h = 0; h < 0x10000; ++h) {
        half exact;
        exact.setBits(static_cast<std::uint16_t>(h));
        const float f = float(exact);
        if (!std::isfinite(f)) continue;
        const std::uint32_t bits = std::bit_cast<std::uint32_t>(f);
        // The half itself, and the floats around the tie with its upper
        // neighbour (13 mantissa bits lower down; the tie at bit 12).
        for (const std::uint32_t offset : {0u, 0xfffu, 0x1000u, 0x1001u, 0x1fffu})
            values.push_back(fromBits(bits + offset));
    }
    for (const float special :
         {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
          std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN(),
          std::numeric_limits<float>::signaling_NaN(), std::numeric_limits<float>::denorm_min(),
          -std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::max(),
          std::numeric_limits<float>::lowest(), 65504.0f, 65519.99f, 65520.0f, -65520.0f})
        values.push_back(special);
    // Counts that leave a remainder after the eight-wide steps.
    for (std::size_t extra = 0; extra < 8; ++extra) {
        values.push_back(fromBits(0x3f800000u + static_cast<std::uint32_t>(extra)));
        EXPECT_EQ(differences(values), 0) << values.size() << " values";
    }
}

TEST(Halves, ManyAtOnceMatchOneByOneAcrossAllFloats) {
    // Every 251st bit pattern: all signs, exponents, NaN payloads and
    // mantissas in 17 M values.
    std::vector<float> values;
    values.reserve((std::uint64_t{1} << 32) / 251 + 1);
    for (std::uint64_t bits = 0; bits < (std::uint64_t{1} << 32); bits += 251)
        values.push_back(fromBits(static_cast<std::uint32_t>(bits)));
    EXPECT_EQ(differences(values), 0);
}

} // namespace cutaway::test
