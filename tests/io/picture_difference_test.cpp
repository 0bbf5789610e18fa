// The picture-quality measure (io/picture_difference.hpp): PSNR and the share
// of pixels a reader sees differ, on display-encoded values.
#include "io/picture_difference.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <stdexcept>
#include <vector>

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
    EXPECT_THROW(comparePictures(flat(2, 2, 0.0f), flat(2, 2, 0.0f), std::vector<bool>(3)),
                 std::invalid_argument);
}

TEST(PictureDifference, AMaskKeepsOnlyItsPixels) {
    // A 7 x 5 image, opaque but for its first column: eroded by one pixel,
    // the interior is columns 2..5 of rows 1..3.
    Image a = flat(7, 5, 0.5f);
    for (int y = 0; y < 5; ++y)
        a.pixel(0, y)[3] = 0.5f;
    const std::vector<bool> inside = opaqueInterior(a, 1);
    std::size_t count = 0;
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x) {
            const bool expected = x >= 2 && x <= 5 && y >= 1 && y <= 3;
            EXPECT_EQ(inside[std::size_t(y) * 7 + std::size_t(x)], expected) << x << "," << y;
            count += expected;
        }
    // A difference outside the mask is not seen; one inside is, over the
    // mask's pixels only. Control: the whole image sees both.
    Image b = a;
    b.pixel(0, 0)[0] = 0.9f;
    EXPECT_TRUE(std::isinf(comparePictures(a, b, inside).psnr));
    b.pixel(3, 2)[0] = 0.6f;
    const PictureDifference masked = comparePictures(a, b, inside);
    EXPECT_EQ(masked.pixels, count);
    EXPECT_NEAR(masked.shareOff, 1.0 / double(count), 1e-12);
    EXPECT_NEAR(comparePictures(a, b).shareOff, 2.0 / 35.0, 1e-12);
}

} // namespace
} // namespace cutaway::test
