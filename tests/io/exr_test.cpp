#include "core/error.hpp"
#include "io/exr.hpp"
#include "io/exr_header.hpp"
#include "temp_dir.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace cutaway {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

std::uint32_t bitsOf(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return bits;
}

Image randomImage(int width, int height, float lo, float hi, unsigned seed) {
    Image image(width, height);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(lo, hi);
    for (float& v : image.rgba)
        v = dist(rng);
    return image;
}

ExrOptions floatOptions() {
    ExrOptions options;
    options.halfFloat = false;
    return options;
}

TEST(Exr, FloatRoundTripIsBitExact) {
    TempDir dir;
    Image image = randomImage(13, 7, -1000.0f, 1000.0f, 1);
    // Values the float path must carry unchanged: tiny, subnormal, huge, -0.
    image.rgba[0] = 1e-30f;
    image.rgba[1] = std::numeric_limits<float>::denorm_min();
    image.rgba[2] = 3e38f;
    image.rgba[3] = -0.0f;
    image.rgba[4] = 0.1f;
    const fs::path path = dir / "float.exr";
    writeExr(path, image, floatOptions());
    const Image back = readExr(path);
    ASSERT_EQ(back.width, 13);
    ASSERT_EQ(back.height, 7);
    ASSERT_EQ(back.rgba.size(), image.rgba.size());
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        ASSERT_EQ(bitsOf(back.rgba[i]), bitsOf(image.rgba[i])) << "at " << i;
    }
    EXPECT_EQ(dir.list(), std::vector<std::string>{"float.exr"}); // no temporary left
}

TEST(Exr, HalfRoundTripRoundsToHalfAndClampsRange) {
    TempDir dir;
    Image image = randomImage(16, 9, -70000.0f, 70000.0f, 2);
    for (std::size_t i = 0; i < 64; ++i)
        image.rgba[i] *= 1e-5f; // small values too
    const float specials[] = {0.1f,
                              1e6f,
                              -1e6f,
                              65504.0f,
                              1e-8f,
                              65519.0f,
                              std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(),
                              std::numeric_limits<float>::quiet_NaN()};
    const std::size_t specialsAt = 100;
    for (std::size_t i = 0; i < std::size(specials); ++i)
        image.rgba[specialsAt + i] = specials[i];

    const fs::path path = dir / "half.exr";
    writeExr(path, image); // half is the default
    const Image back = readExr(path);
    ASSERT_EQ(back.width, 16);
    ASSERT_EQ(back.height, 9);
    int clamped = 0;
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        const float x = image.rgba[i], r = back.rgba[i];
        if (std::isnan(x)) {
            EXPECT_EQ(r, 0.0f) << "NaN must be written as 0";
        } else if (std::fabs(x) > 65504.0f) {
            EXPECT_EQ(r, std::copysign(65504.0f, x)) << "at " << i << " x=" << x;
            ++clamped;
        } else {
            EXPECT_LE(std::fabs(r - x), std::fabs(x) * 0x1p-10f + 6e-8f) << "at " << i;
        }
    }
    EXPECT_GT(clamped, 4);                  // the specials plus random values beyond the half range
    EXPECT_NE(back.rgba[specialsAt], 0.1f); // 0.1 has no exact half: proves it was half

    // A half file of noise is about half the size of the float one.
    const fs::path floatPath = dir / "float.exr";
    writeExr(floatPath, image, floatOptions());
    EXPECT_LT(fs::file_size(path) * 3, fs::file_size(floatPath) * 2);
}

// Every compression is lossless and is the one the header names. A smooth
// image (as renders are) shrinks under each but RLE, which needs runs of equal
// bytes; noise in its last rows keeps PIZ and ZIP from ties.
TEST(Exr, EachCompressionIsNamedInTheHeaderAndLossless) {
    const struct {
        ExrCompression compression;
        int code; // OpenEXR's
    } kCases[] = {{ExrCompression::None, 0},
                  {ExrCompression::Rle, 1},
                  {ExrCompression::Zips, 2},
                  {ExrCompression::Zip, 3},
                  {ExrCompression::Piz, 4}};
    TempDir dir;
    Image image = randomImage(64, 48, 0.0f, 1.0f, 3);
    for (int y = 0; y < 40; ++y) {
        for (int x = 0; x < 64; ++x) {
            float* p = image.pixel(x, y);
            p[0] = float(x) / 64.0f, p[1] = float(y) / 48.0f, p[2] = 0.5f, p[3] = 1.0f;
        }
    }
    const std::vector<float> ids(64 * 48, 2.0f);
    for (const bool half : {true, false}) {
        std::uintmax_t uncompressed = 0;
        Image expected = image;
        for (const auto& c : kCases) {
            ExrOptions options;
            options.halfFloat = half;
            options.compression = c.compression;
            options.channels = {{"operator_id", &ids}};
            const fs::path path =
                dir / ("c" + std::to_string(c.code) + (half ? "h" : "f") + ".exr");
            writeExr(path, image, options);
            EXPECT_EQ(test::exrCompressionCode(path), c.code) << path;
            // Lossless: the float file reads back bit for bit, the half one
            // as the uncompressed one (the first case) does.
            const Image back = readExr(path);
            if (c.compression == ExrCompression::None) {
                uncompressed = fs::file_size(path);
                if (half) expected = back;
            }
            ASSERT_EQ(back.rgba.size(), expected.rgba.size());
            for (std::size_t i = 0; i < back.rgba.size(); ++i)
                ASSERT_EQ(bitsOf(back.rgba[i]), bitsOf(expected.rgba[i])) << path << " at " << i;
            EXPECT_EQ(readExrChannel(path, "operator_id"), ids) << path;
            if (c.compression != ExrCompression::None && c.compression != ExrCompression::Rle) {
                EXPECT_LT(fs::file_size(path), uncompressed) << path;
            }
        }
    }
}

TEST(Exr, OrientationIsPreserved) {
    for (const bool half : {true, false}) {
        TempDir dir;
        Image image(7, 5);
        float* p = image.pixel(3, 1);
        p[0] = 0.25f, p[1] = 0.5f, p[2] = 0.75f, p[3] = 1.0f;
        const fs::path path = dir / "orient.exr";
        ExrOptions options;
        options.halfFloat = half;
        writeExr(path, image, options);
        const Image back = readExr(path);
        ASSERT_EQ(back.width, 7);
        ASSERT_EQ(back.height, 5);
        for (int y = 0; y < 5; ++y) {
            for (int x = 0; x < 7; ++x) {
                const bool set = x == 3 && y == 1;
                const float* q = back.pixel(x, y);
                EXPECT_EQ(q[0], set ? 0.25f : 0.0f) << x << "," << y;
                EXPECT_EQ(q[1], set ? 0.5f : 0.0f) << x << "," << y;
                EXPECT_EQ(q[2], set ? 0.75f : 0.0f) << x << "," << y;
                EXPECT_EQ(q[3], set ? 1.0f : 0.0f) << x << "," << y;
            }
        }
    }
}

TEST(Exr, StringAttributesRoundTrip) {
    TempDir dir;
    ExrOptions options;
    options.attributes = {{"frame", "42"}, {"scene", "scenes/head cut.json"}, {"empty", ""}};
    const fs::path path = dir / "attr.exr";
    writeExr(path, Image(2, 3), options);
    EXPECT_EQ(readExrStringAttribute(path, "frame"), "42");
    EXPECT_EQ(readExrStringAttribute(path, "scene"), "scenes/head cut.json");
    EXPECT_EQ(readExrStringAttribute(path, "empty"), "");
    EXPECT_EQ(readExrStringAttribute(path, "software"), "cutaway " CUTAWAY_VERSION);
    EXPECT_EQ(readExrStringAttribute(path, "absent"), "");
    // A standard attribute of another type is not a string attribute.
    EXPECT_EQ(readExrStringAttribute(path, "compression"), "");
}

// The standard framesPerSecond attribute compositors read: NTSC rates as
// their exact rationals, others in lowest terms; none unless asked for.
TEST(Exr, FramesPerSecondIsTheStandardRational) {
    const auto dir = std::filesystem::temp_directory_path() / "cutaway_exr_fps";
    std::filesystem::create_directories(dir);
    const Image img = randomImage(5, 3, 0.0f, 1.0f, 7);
    for (const auto& [fps, expected] :
         {std::pair{24.0, std::pair{24, 1u}}, std::pair{29.97, std::pair{30000, 1001u}},
          std::pair{23.976, std::pair{24000, 1001u}}, std::pair{12.5, std::pair{25, 2u}}}) {
        ExrOptions options;
        options.framesPerSecond = fps;
        writeExr(dir / "f.exr", img, options);
        EXPECT_EQ(test::exrFramesPerSecond(dir / "f.exr"), expected) << fps;
    }
    writeExr(dir / "none.exr", img, {});
    EXPECT_EQ(test::exrFramesPerSecond(dir / "none.exr"), (std::pair{0, 0u}));
    std::filesystem::remove_all(dir);
}

TEST(Exr, MissingFileIsInputErrorNamingIt) {
    TempDir dir;
    const fs::path path = dir / "missing.exr";
    try {
        readExr(path);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
    EXPECT_THROW(readExrStringAttribute(path, "frame"), InputError);
}

TEST(Exr, NonExrFileIsInputError) {
    TempDir dir;
    const fs::path path = dir / "text.exr";
    std::ofstream(path) << "this is not an OpenEXR file, just some text\n";
    try {
        readExr(path);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
    EXPECT_THROW(readExrStringAttribute(path, "frame"), InputError);
}

TEST(Exr, TruncatedFileIsInputError) {
    TempDir dir;
    const fs::path path = dir / "cut.exr";
    writeExr(path, randomImage(64, 64, 0.0f, 1.0f, 3), floatOptions());
    fs::resize_file(path, fs::file_size(path) / 2);
    EXPECT_THROW(readExr(path), InputError);
}

TEST(Exr, WriteIntoMissingFolderIsRuntimeError) {
    TempDir dir;
    const fs::path folder = dir / "absent";
    try {
        writeExr(folder / "out.exr", Image(2, 2));
        FAIL() << "expected RuntimeError";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(folder.string()), std::string::npos) << e.what();
    }
    EXPECT_TRUE(dir.list().empty());
}

TEST(Exr, InconsistentImageIsRejected) {
    TempDir dir;
    Image image(4, 4);
    image.rgba.resize(10);
    EXPECT_THROW(writeExr(dir / "bad.exr", image), RuntimeError);
    EXPECT_TRUE(dir.list().empty());
}

} // namespace
} // namespace cutaway
