// The picture-quality measure (io/picture_difference.hpp): PSNR and the share
// of pixels a reader sees differ, on display-encoded values.
#include "io/picture_difference.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <stdexcept>

namespace cutaway::test {
namespace {

Image flat(int w, int h, float value) {
    Image image(w, h);
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
        image.rgba[i] = (i % 4 == 3) ? 1.0f : value;
    return image;
}

TEST(PictureDifference, TheSameImageIsInfinitelyClose) {
    const Image a = flat(8, 4, 0.3f);
    const PictureDifference d = comparePictures(a, a);
    EXPECT_TRUE(std::isinf(d.psnr));
    EXPECT_EQ(d.shareOff, 0.0);
    EXPECT_EQ(d.maxError, 0.0);
}

TEST(PictureDifference, ComparesDisplayEncodedValuesClippedToOne) {
    // One pixel of 16 off by a known encoded amount, in one channel.
    Image a = flat(4, 4, 0.5f), b = a;
    b.pixel(1, 2)[1] = 0.6f;
    const double e = std::pow(double(0.6f), 1 / 2.2) - std::pow(0.5, 1 / 2.2);
    PictureDifference d = comparePictures(a, b);
    EXPECT_NEAR(d.maxError, e, 1e-6);
    EXPECT_NEAR(d.psnr, 10.0 * std::log10(48.0 / (e * e)), 1e-6);
    EXPECT_NEAR(d.shareOff, 1.0 / 16.0, 1e-12);
    // Linear values past 1 are clipped before they are compared: a highlight
    // at 3 looks as white as one at 1.5.
    Image bright = flat(4, 4, 3.0f), brighter = flat(4, 4, 1.5f);
    EXPECT_TRUE(std::isinf(comparePictures(bright, brighter).psnr));
    // Alpha is not compared (the background is composited already).
    Image clear = a;
    clear.pixel(0, 0)[3] = 0.0f;
    EXPECT_TRUE(std::isinf(comparePictures(a, clear).psnr));
}

TEST(PictureDifference, APixelCountsAsOffOnlyPastTheVisibleStep) {
    Image a = flat(2, 1, 0.5f), b = a;
    const double base = std::pow(0.5, 1 / 2.2);
    // Just under and just over 4/255 in the encoded value.
    b.pixel(0, 0)[0] = float(std::pow(base + 3.9 / 255.0, 2.2));
    b.pixel(1, 0)[2] = float(std::pow(base + 4.1 / 255.0, 2.2));
    EXPECT_NEAR(comparePictures(a, b).shareOff, 0.5, 1e-12);
}

TEST(PictureDifference, RefusesImagesOfDifferentSizes) {
    EXPECT_THROW(comparePictures(flat(2, 2, 0.0f), flat(2, 3, 0.0f)), std::invalid_argument);
}

} // namespace
} // namespace cutaway::test
