// Reading EXR files cutaway did not write: a minimal uncompressed scanline
// EXR, built byte by byte (the test links no OpenEXR), with channels of each
// pixel type, no B and no A, and a data window away from the origin.
#include "io/exr.hpp"
#include "temp_dir.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <utility>
#include <vector>

namespace cutaway {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

struct Bytes {
    std::vector<char> data;
    void raw(const void* p, std::size_t n) {
        // resize + memcpy rather than insert(), which trips a false GCC 12
        // -Wstringop-overflow when inlined into an empty vector.
        const std::size_t at = data.size();
        data.resize(at + n);
        std::memcpy(data.data() + at, p, n);
    }
    void str(const std::string& s) { raw(s.c_str(), s.size() + 1); } // with the NUL
    // Host order: x86 and ARM Linux are little-endian, as EXR is.
    template <typename T>
    void le(T v) {
        raw(&v, sizeof v);
    }
    void attr(const std::string& name, const std::string& type, const Bytes& value) {
        str(name);
        str(type);
        le(static_cast<std::int32_t>(value.data.size()));
        raw(value.data.data(), value.data.size());
    }
};

Bytes box(std::int32_t x0, std::int32_t y0, std::int32_t x1, std::int32_t y1) {
    Bytes b;
    for (std::int32_t v : {x0, y0, x1, y1})
        b.le(v);
    return b;
}

TEST(Exr, ReadsAnyPixelTypeAndFillsMissingChannels) {
    // Channels, alphabetical as EXR requires: G UINT, R HALF, Z FLOAT (ignored).
    constexpr int kWidth = 3, kHeight = 2, kX0 = 10, kY0 = 20;
    const std::uint32_t green[kHeight][kWidth] = {{0, 7, 100000}, {1, 2, 3}};
    const std::uint16_t red[kHeight][kWidth] = {{0x3E00, 0xC000, 0x3400},  // 1.5, -2, 0.25
                                                {0x0000, 0x3C00, 0x7BFF}}; // 0, 1, 65504
    const float redValue[kHeight][kWidth] = {{1.5f, -2.0f, 0.25f}, {0.0f, 1.0f, 65504.0f}};

    Bytes channels;
    for (auto [name, type] : {std::pair{"G", 0}, std::pair{"R", 1}, std::pair{"Z", 2}}) {
        channels.str(name);
        channels.le(static_cast<std::int32_t>(type));
        channels.le(std::uint32_t{0}); // pLinear + 3 reserved bytes
        channels.le(std::int32_t{1});  // x sampling
        channels.le(std::int32_t{1});  // y sampling
    }
    channels.le(char{0});
    Bytes none, increasing, one, center;
    none.le(std::uint8_t{0});       // NO_COMPRESSION
    increasing.le(std::uint8_t{0}); // INCREASING_Y
    one.le(1.0f);
    center.le(0.0f), center.le(0.0f);

    Bytes file;
    file.le(std::int32_t{20000630}); // magic
    file.le(std::int32_t{2});        // version 2, single-part scanline
    file.attr("channels", "chlist", channels);
    file.attr("compression", "compression", none);
    file.attr("dataWindow", "box2i", box(kX0, kY0, kX0 + kWidth - 1, kY0 + kHeight - 1));
    file.attr("displayWindow", "box2i", box(0, 0, 99, 99));
    file.attr("lineOrder", "lineOrder", increasing);
    file.attr("pixelAspectRatio", "float", one);
    file.attr("screenWindowCenter", "v2f", center);
    file.attr("screenWindowWidth", "float", one);
    file.le(char{0}); // end of header
    const std::int32_t lineBytes = kWidth * (4 + 2 + 4);
    const std::size_t tableAt = file.data.size();
    for (int y = 0; y < kHeight; ++y) {
        file.le(static_cast<std::uint64_t>(tableAt + kHeight * 8 + y * (8 + lineBytes)));
    }
    for (int y = 0; y < kHeight; ++y) {
        file.le(static_cast<std::int32_t>(kY0 + y));
        file.le(lineBytes);
        for (int x = 0; x < kWidth; ++x)
            file.le(green[y][x]);
        for (int x = 0; x < kWidth; ++x)
            file.le(red[y][x]);
        for (int x = 0; x < kWidth; ++x)
            file.le(-5.0f);
    }

    TempDir dir;
    const fs::path path = dir / "handmade.exr";
    std::ofstream(path, std::ios::binary)
        .write(file.data.data(), static_cast<std::streamsize>(file.data.size()));
    const Image image = readExr(path);
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const float* p = image.pixel(x, y);
            EXPECT_EQ(p[0], redValue[y][x]) << x << "," << y;
            EXPECT_EQ(p[1], static_cast<float>(green[y][x])) << x << "," << y;
            EXPECT_EQ(p[2], 0.0f) << "missing B reads as 0";
            EXPECT_EQ(p[3], 1.0f) << "missing A reads as 1";
        }
    }
    EXPECT_EQ(readExrStringAttribute(path, "software"), "");
}

} // namespace
} // namespace cutaway
