#include "core/error.hpp"
#include "io/png.hpp"
#include "temp_dir.hpp"

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <sys/resource.h>
#include <vector>
#include <zlib.h>

namespace cutaway {
namespace {

namespace fs = std::filesystem;
using test::TempDir;
using PngBytes = std::vector<std::uint8_t>;

std::uint32_t be32(const std::uint8_t* p) {
    return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

// An independent decoder for what writePng may produce: 8-bit RGBA,
// non-interlaced, any of the five filters. Fails the test on any violation.
struct Decoded {
    int width = 0, height = 0;
    std::vector<std::string> chunkTypes;
    std::vector<std::uint32_t> idatSizes;
    std::map<std::string, PngBytes> payloads; ///< each chunk type's last payload
    std::vector<std::uint8_t> srgb;           ///< sRGB chunk payload
    PngBytes rgba;                            ///< width * height * 4
    std::vector<int> filters;                 ///< each row's filter type
    std::vector<int> bestFilters;             ///< each row's filter of the least sum of |residual|
    const std::uint8_t* pixel(int x, int y) const {
        return &rgba[(std::size_t(y) * width + x) * 4];
    }
};

int paeth(int a, int b, int c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    if (pa <= pb && pa <= pc) return a;
    return pb <= pc ? b : c;
}

void decode(const fs::path& path, Decoded& out) {
    std::ifstream in(path, std::ios::binary);
    const PngBytes file{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const PngBytes signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    ASSERT_GE(file.size(), signature.size());
    ASSERT_TRUE(std::equal(signature.begin(), signature.end(), file.begin()));

    PngBytes idat;
    std::size_t at = signature.size();
    while (at < file.size()) {
        ASSERT_LE(at + 12, file.size()) << "truncated chunk";
        const std::uint32_t length = be32(&file[at]);
        ASSERT_LE(at + 12 + length, file.size());
        const std::string type(reinterpret_cast<const char*>(&file[at + 4]), 4);
        const std::uint8_t* data = &file[at + 8];
        const uLong crc = crc32(0L, &file[at + 4], length + 4);
        ASSERT_EQ(be32(data + length), static_cast<std::uint32_t>(crc)) << "CRC of " << type;
        out.chunkTypes.push_back(type);
        out.payloads[type].assign(data, data + length);
        if (type == "IHDR") {
            ASSERT_EQ(length, 13u);
            out.width = static_cast<int>(be32(data));
            out.height = static_cast<int>(be32(data + 4));
            EXPECT_EQ(data[8], 8) << "bit depth";
            EXPECT_EQ(data[9], 6) << "colour type RGBA";
            EXPECT_EQ(data[10], 0) << "compression";
            EXPECT_EQ(data[11], 0) << "filter method";
            EXPECT_EQ(data[12], 0) << "interlace";
        } else if (type == "sRGB") {
            out.srgb.assign(data, data + length);
        } else if (type == "IDAT") {
            idat.insert(idat.end(), data, data + length);
            out.idatSizes.push_back(length);
        }
        at += 12 + length;
    }
    ASSERT_FALSE(out.chunkTypes.empty());
    EXPECT_EQ(out.chunkTypes.front(), "IHDR");
    EXPECT_EQ(out.chunkTypes.back(), "IEND");
    ASSERT_GT(out.width, 0);
    ASSERT_GT(out.height, 0);

    const std::size_t rowBytes = std::size_t(out.width) * 4;
    PngBytes raw((rowBytes + 1) * out.height);
    uLongf rawSize = static_cast<uLongf>(raw.size());
    ASSERT_EQ(uncompress(raw.data(), &rawSize, idat.data(), static_cast<uLong>(idat.size())), Z_OK);
    ASSERT_EQ(rawSize, raw.size());

    out.rgba.assign(rowBytes * out.height, 0);
    for (int y = 0; y < out.height; ++y) {
        const std::uint8_t filter = raw[y * (rowBytes + 1)];
        ASSERT_LE(filter, 4) << "row " << y;
        out.filters.push_back(filter);
        const std::uint8_t* src = &raw[y * (rowBytes + 1) + 1];
        std::uint8_t* row = &out.rgba[y * rowBytes];
        const std::uint8_t* prev = y > 0 ? row - rowBytes : nullptr;
        auto predict = [&](int f, std::size_t i) {
            const int a = i >= 4 ? row[i - 4] : 0;
            const int b = prev ? prev[i] : 0;
            const int c = prev && i >= 4 ? prev[i - 4] : 0;
            return f == 1 ? a : f == 2 ? b : f == 3 ? (a + b) / 2 : f == 4 ? paeth(a, b, c) : 0;
        };
        for (std::size_t i = 0; i < rowBytes; ++i)
            row[i] = static_cast<std::uint8_t>(src[i] + predict(filter, i));
        // The PNG spec's heuristic, on the decoded row: the first filter
        // whose residuals, as signed bytes, have the least sum of magnitudes.
        long best = -1;
        for (int f = 0; f < 5; ++f) {
            long sum = 0;
            for (std::size_t i = 0; i < rowBytes; ++i)
                sum += std::abs(static_cast<std::int8_t>(row[i] - predict(f, i)));
            if (best < 0 || sum < best) {
                best = sum;
                if (f == 0)
                    out.bestFilters.push_back(0);
                else
                    out.bestFilters.back() = f;
            }
        }
    }
}

void setPixel(Image& image, int x, int y, float r, float g, float b, float a) {
    float* p = image.pixel(x, y);
    p[0] = r, p[1] = g, p[2] = b, p[3] = a;
}

TEST(Png, LinearToSrgbCurve) {
    EXPECT_EQ(linearToSrgb(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(linearToSrgb(1.0f), 1.0f);
    EXPECT_NEAR(linearToSrgb(0.5f), 0.735357f, 1e-5f);
    EXPECT_NEAR(linearToSrgb(0.18f), 0.461356f, 1e-5f);
    // Continuous at the knee between the linear and the power segment.
    const float knee = 0.0031308f;
    EXPECT_NEAR(linearToSrgb(std::nextafter(knee, 0.0f)), linearToSrgb(knee), 1e-5f);
    EXPECT_NEAR(linearToSrgb(std::nextafter(knee, 1.0f)), linearToSrgb(knee), 1e-5f);
    EXPECT_NEAR(linearToSrgb(knee), 12.92f * knee, 1e-6f);
    // Strictly increasing over [0,1].
    float previous = -1.0f;
    for (int i = 0; i <= 10000; ++i) {
        const float v = linearToSrgb(static_cast<float>(i) / 10000.0f);
        ASSERT_GT(v, previous) << "at " << i;
        previous = v;
    }
    // Clamped outside [0,1].
    EXPECT_EQ(linearToSrgb(-1.0f), 0.0f);
    EXPECT_EQ(linearToSrgb(4.0f), 1.0f);
    EXPECT_EQ(linearToSrgb(std::nanf("")), 0.0f);
}

// The table-driven byte is the rounded curve: checked here on every 61st
// float of [0, 1] (17 M of them; all 1.07 G agreed when it was written) and
// around each byte's first value, which a wrong bucket or step would shift.
TEST(Png, SrgbByteIsTheRoundedCurve) {
    auto rounded = [](float x) {
        const float v = linearToSrgb(x);
        return v >= 1.0f ? 255 : static_cast<int>(std::lround(v * 255.0f));
    };
    std::uint32_t one;
    const float oneF = 1.0f;
    std::memcpy(&one, &oneF, sizeof one);
    int changes = 0, previous = 0;
    for (std::uint32_t bits = 0; bits <= one; bits += 61) {
        float x;
        std::memcpy(&x, &bits, sizeof x);
        const int byte = linearToSrgbByte(x);
        ASSERT_EQ(byte, rounded(x)) << "at " << x;
        ASSERT_GE(byte, previous) << "at " << x;
        changes += byte != previous;
        previous = byte;
    }
    EXPECT_EQ(changes, 255);
    for (int b = 0; b < 255; ++b) {
        // The first linear value of byte b + 1 (the curve inverted), give or take.
        const float s = (static_cast<float>(b) + 0.5f) / 255.0f;
        float x = s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f);
        for (int i = 0; i < 64; ++i, x = std::nextafter(x, 0.0f))
            ASSERT_EQ(linearToSrgbByte(x), rounded(x)) << "at " << x;
        for (int i = 0; i < 64; ++i, x = std::nextafter(x, 2.0f))
            ASSERT_EQ(linearToSrgbByte(x), rounded(x)) << "at " << x;
    }
    EXPECT_EQ(linearToSrgbByte(std::nanf("")), 0);
    EXPECT_EQ(linearToSrgbByte(-1.0f), 0);
    EXPECT_EQ(linearToSrgbByte(1.0f), 255);
    EXPECT_EQ(linearToSrgbByte(3e38f), 255);
}

TEST(Png, EncodesColourAndAlpha) {
    TempDir dir;
    Image image(5, 3);
    setPixel(image, 0, 0, 0.5f, 0.5f, 0.5f, 1.0f);    // opaque linear grey
    setPixel(image, 1, 0, 0.25f, 0.25f, 0.25f, 0.5f); // same grey, premultiplied by 0.5
    setPixel(image, 2, 0, 0.0f, 0.0f, 0.0f, 0.0f);    // transparent
    setPixel(image, 3, 0, 1.0f, 0.0f, 0.0f, 1.0f);    // pure red
    setPixel(image, 4, 0, 8.0f, -1.0f, 0.5f, 2.0f);   // out of range: clamped
    setPixel(image, 0, 2, 0.001f, 0.0f, 0.0f, 1.0f);  // below the knee: 12.92 * 0.001
    setPixel(image, 4, 2, 0.2f, 0.4f, 0.6f, 1.0f);    // bottom-right corner
    const fs::path path = dir / "out.png";
    writePng(path, image);
    EXPECT_EQ(dir.list(), std::vector<std::string>{"out.png"});

    Decoded png;
    ASSERT_NO_FATAL_FAILURE(decode(path, png));
    ASSERT_EQ(png.width, 5);
    ASSERT_EQ(png.height, 3);
    EXPECT_EQ(png.srgb, std::vector<std::uint8_t>{0}) << "sRGB chunk, perceptual intent";

    auto expectPixel = [&](int x, int y, int r, int g, int b, int a) {
        const std::uint8_t* p = png.pixel(x, y);
        EXPECT_NEAR(p[0], r, 1) << x << "," << y;
        EXPECT_NEAR(p[1], g, 1) << x << "," << y;
        EXPECT_NEAR(p[2], b, 1) << x << "," << y;
        EXPECT_NEAR(p[3], a, 1) << x << "," << y;
    };
    expectPixel(0, 0, 188, 188, 188, 255);
    expectPixel(1, 0, 188, 188, 188, 128);
    EXPECT_EQ(png.pixel(2, 0)[3], 0);
    expectPixel(3, 0, 255, 0, 0, 255);
    // 8/2 -> 1 clamped: 255; -1 -> 0; 0.5/1 -> 188; alpha 2 -> 1.
    expectPixel(4, 0, 255, 0, 188, 255);
    expectPixel(0, 2, 3, 0, 0, 255); // 12.92 * 0.001 * 255 = 3.3
    expectPixel(4, 2, 124, 170, 203, 255);
    expectPixel(2, 1, 0, 0, 0, 0);
}

TEST(Png, LargerImageRoundTripsThroughAllFilters) {
    // A gradient plus noise makes the encoder use more than one filter; the
    // decoder checks every pixel against the expected 8-bit value.
    TempDir dir;
    const int width = 97, height = 61;
    Image image(width, height);
    std::uint32_t state = 12345;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            state = state * 1664525u + 1013904223u;
            const float noise = static_cast<float>(state >> 24) / 255.0f;
            const float a = y < height / 2 ? 1.0f : noise;
            setPixel(image, x, y, a * float(x) / width, a * float(y) / height, a * noise, a);
        }
    }
    const fs::path path = dir / "big.png";
    writePng(path, image);
    Decoded png;
    ASSERT_NO_FATAL_FAILURE(decode(path, png));
    ASSERT_EQ(png.width, width);
    ASSERT_EQ(png.height, height);
    EXPECT_EQ(png.filters, png.bestFilters);
    EXPECT_GE(std::set<int>(png.filters.begin(), png.filters.end()).size(), 3u);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float* in = image.pixel(x, y);
            const std::uint8_t* p = png.pixel(x, y);
            const float a = in[3];
            ASSERT_NEAR(p[3], a * 255.0f, 0.51f) << x << "," << y;
            if (a < 1.0f / 255.0f) continue;
            for (int c = 0; c < 3; ++c) {
                const float expected = 255.0f * linearToSrgb(in[c] / a);
                ASSERT_NEAR(p[c], expected, 0.51f) << x << "," << y << " channel " << c;
            }
        }
    }
}

TEST(Png, ReplacesAnExistingFile) {
    TempDir dir;
    const fs::path path = dir / "frame.png";
    std::ofstream(path) << "stale";
    Image image(1, 1);
    setPixel(image, 0, 0, 1.0f, 1.0f, 1.0f, 1.0f);
    writePng(path, image);
    Decoded png;
    ASSERT_NO_FATAL_FAILURE(decode(path, png));
    EXPECT_EQ(png.pixel(0, 0)[0], 255);
    EXPECT_EQ(dir.list(), std::vector<std::string>{"frame.png"});
}

TEST(Png, WriteIntoMissingFolderIsRuntimeError) {
    TempDir dir;
    const fs::path folder = dir / "absent";
    try {
        writePng(folder / "out.png", Image(2, 2));
        FAIL() << "expected RuntimeError";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(folder.string()), std::string::npos) << e.what();
    }
    EXPECT_TRUE(dir.list().empty());
}

// Opaque random colours: about as incompressible as a preview gets, so a
// 1024x512 one deflates to more than 1 MiB, the size of an IDAT chunk.
Image noiseImage(int width, int height) {
    Image image(width, height);
    std::uint32_t state = 777;
    for (float& v : image.rgba) {
        state = state * 1664525u + 1013904223u;
        v = static_cast<float>(state >> 8) / 16777216.0f;
    }
    for (std::size_t i = 3; i < image.rgba.size(); i += 4)
        image.rgba[i] = 1.0f;
    return image;
}

PngBytes fileBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Only the image and its colour space: no time stamp or text, which would make
// a rerun's file differ. gAMA and cHRM are sRGB's, for decoders that ignore
// sRGB; IDAT chunks hold 1 MiB each but the last.
TEST(Png, ChunksAreTheColourSpaceAndTheImageOnly) {
    TempDir dir;
    const fs::path path = dir / "noise.png";
    writePng(path, noiseImage(1024, 512));
    Decoded png;
    ASSERT_NO_FATAL_FAILURE(decode(path, png));
    ASSERT_GE(png.idatSizes.size(), 2u) << "the image should need more than one IDAT";
    std::vector<std::string> expected = {"IHDR", "sRGB", "gAMA", "cHRM"};
    expected.insert(expected.end(), png.idatSizes.size(), "IDAT");
    expected.push_back("IEND");
    EXPECT_EQ(png.chunkTypes, expected);
    for (std::size_t i = 0; i + 1 < png.idatSizes.size(); ++i)
        EXPECT_EQ(png.idatSizes[i], 1u << 20) << "IDAT " << i;
    EXPECT_LE(png.idatSizes.back(), 1u << 20);
    ASSERT_EQ(png.payloads["gAMA"].size(), 4u);
    EXPECT_EQ(be32(png.payloads["gAMA"].data()), 45455u);
    ASSERT_EQ(png.payloads["cHRM"].size(), 32u);
    const std::uint32_t chrm[] = {31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000};
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(be32(png.payloads["cHRM"].data() + 4 * i), chrm[i]) << "cHRM value " << i;
    EXPECT_EQ(png.filters, png.bestFilters);
}

TEST(Png, SameImageSameBytes) {
    TempDir dir;
    Image image = noiseImage(300, 200);
    writePng(dir / "a.png", image);
    writePng(dir / "b.png", image);
    EXPECT_EQ(fileBytes(dir / "a.png"), fileBytes(dir / "b.png"));
    // Control: the comparison sees a single pixel's change.
    image.pixel(150, 100)[0] = 0.0f;
    writePng(dir / "c.png", image);
    EXPECT_NE(fileBytes(dir / "a.png"), fileBytes(dir / "c.png"));
}

// Wider than libpng's default limit of a million pixels a side; PNG allows
// 2^31 - 1.
TEST(Png, WritesAMillionPixelWideRow) {
    TempDir dir;
    const int width = 1'000'001;
    Image image(width, 1);
    setPixel(image, width - 1, 0, 1.0f, 0.0f, 0.0f, 1.0f);
    const fs::path path = dir / "wide.png";
    writePng(path, image);
    Decoded png;
    ASSERT_NO_FATAL_FAILURE(decode(path, png));
    ASSERT_EQ(png.width, width);
    EXPECT_EQ(png.pixel(width - 1, 0)[0], 255);
    EXPECT_EQ(png.pixel(width - 1, 0)[3], 255);
    EXPECT_EQ(png.pixel(width - 2, 0)[3], 0);
}

// For a death test's child: writes `image` with files limited to `limit`
// bytes (RLIMIT_FSIZE with its signal ignored, so a write past it fails with
// EFBIG as one on a full disk fails with ENOSPC). Exits 0 when writePng
// succeeds, 1 when it throws RuntimeError (message on stderr), 2 otherwise.
[[noreturn]] void writeWithFileSizeLimit(const fs::path& path, const Image& image, rlim_t limit) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit small{limit, limit};
    if (setrlimit(RLIMIT_FSIZE, &small) != 0) std::_Exit(3);
    try {
        writePng(path, image);
    } catch (const RuntimeError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        std::_Exit(1);
    } catch (...) {
        std::_Exit(2);
    }
    std::_Exit(0);
}

// A write that fails part way (here past the first 1 MiB IDAT, while rows are
// still being encoded) names the file and the system's reason, as for a full
// disk, and leaves neither the file nor its temporary.
TEST(Png, AFailedWriteNamesTheCauseAndLeavesNoFile) {
    TempDir dir;
    const Image noise = noiseImage(1024, 512);
    const std::string reason = std::string("\\(") + std::strerror(EFBIG) + "\\)";
    EXPECT_EXIT(writeWithFileSizeLimit(dir / "noise.png", noise, 64 * 1024),
                testing::ExitedWithCode(1), "cannot write .*noise\\.png " + reason);
    EXPECT_TRUE(dir.list().empty());
    // Control: under the same limit a small image is written.
    EXPECT_EXIT(writeWithFileSizeLimit(dir / "small.png", noiseImage(8, 8), 64 * 1024),
                testing::ExitedWithCode(0), "");
    EXPECT_EQ(dir.list(), std::vector<std::string>{"small.png"});
}

} // namespace
} // namespace cutaway
