#pragma once
// Helpers for the volume tests: temporary folders, raw bytes, gzip, and
// hand-written NIfTI-1 headers (so the reader is checked against the format,
// not against our own writer).
#include "core/error.hpp"
#include "volume/volume.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <unistd.h>
#include <vector>
#include <zlib.h>

namespace cutaway::test {

class VolumeFiles : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = std::filesystem::temp_directory_path() /
                ("cutaway_volume_" + std::to_string(::getpid()) + "_" +
                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(m_dir);
        std::filesystem::create_directories(m_dir);
    }
    void TearDown() override { std::filesystem::remove_all(m_dir); }

    std::filesystem::path path(const std::string& name) const { return m_dir / name; }
    std::filesystem::path writeFile(const std::string& name, const std::string& bytes) const {
        std::ofstream(m_dir / name, std::ios::binary) << bytes;
        return m_dir / name;
    }
    std::filesystem::path m_dir;
};

inline std::string bytesOf(const void* p, std::size_t n) {
    return std::string(static_cast<const char*>(p), n);
}

/// gzip (not zlib) compression of `data`.
inline std::string gzip(const std::string& data) {
    z_stream s{};
    deflateInit2(&s, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
    std::string out(deflateBound(&s, data.size()) + 64, '\0');
    s.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    s.avail_in = static_cast<uInt>(data.size());
    s.next_out = reinterpret_cast<Bytef*>(out.data());
    s.avail_out = static_cast<uInt>(out.size());
    deflate(&s, Z_FINISH);
    out.resize(s.total_out);
    deflateEnd(&s);
    return out;
}

inline std::string byteSwapped(std::string data, std::size_t width) {
    for (std::size_t i = 0; i + width <= data.size(); i += width)
        std::reverse(data.begin() + static_cast<std::ptrdiff_t>(i),
                     data.begin() + static_cast<std::ptrdiff_t>(i + width));
    return data;
}

/// A NIfTI-1 header (348 bytes) plus the 4-byte extension flag, little endian.
struct NiftiHeader {
    std::int16_t dims[8] = {3, 1, 1, 1, 1, 1, 1, 1};
    std::int16_t datatype = 2;
    std::int16_t bitpix = 8;
    float pixdim[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    float voxOffset = 352;
    float sclSlope = 0;
    float sclInter = 0;
    std::int32_t sizeofHdr = 348;
    const char* magic = "n+1";
    // Orientation (NIfTI's RAS space): the qform (quaternion b, c, d, qfac in
    // pixdim[0], offset) and the sform (rows of the affine).
    std::int16_t qformCode = 0;
    std::int16_t sformCode = 0;
    float quatern[3] = {0, 0, 0};
    float qoffset[3] = {0, 0, 0};
    float srow[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};

    std::string bytes() const {
        std::string h(352, '\0');
        auto put = [&](std::size_t at, const void* p, std::size_t n) { std::memcpy(&h[at], p, n); };
        put(0, &sizeofHdr, 4);
        put(40, dims, 16);
        put(70, &datatype, 2);
        put(72, &bitpix, 2);
        put(76, pixdim, 32);
        put(108, &voxOffset, 4);
        put(112, &sclSlope, 4);
        put(116, &sclInter, 4);
        put(252, &qformCode, 2);
        put(254, &sformCode, 2);
        put(256, quatern, 12);
        put(268, qoffset, 12);
        put(280, srow, 48);
        put(344, magic, std::strlen(magic) + 1);
        return h;
    }

    /// The same header as NIfTI-2 (540 bytes and the extension flag: 64-bit
    /// dims and offset, 32-bit codes, doubles), as the format's spec lays it
    /// out; `magic` "n+2" (or "ni2"), vox_offset at least 544.
    std::string nifti2(const char* magic2 = "n+2") const {
        std::string h(544, '\0');
        auto put = [&](std::size_t at, const void* p, std::size_t n) { std::memcpy(&h[at], p, n); };
        auto putDoubles = [&](std::size_t at, const float* v, std::size_t n) {
            for (std::size_t i = 0; i < n; ++i) {
                const double d = v[i];
                put(at + 8 * i, &d, 8);
            }
        };
        const std::int32_t size = 540;
        put(0, &size, 4);
        put(4, magic2, std::strlen(magic2));
        put(4 + std::strlen(magic2), "\0\r\n\032\n", 5);
        put(12, &datatype, 2);
        put(14, &bitpix, 2);
        for (std::size_t i = 0; i < 8; ++i) {
            const std::int64_t d = dims[i];
            put(16 + 8 * i, &d, 8);
        }
        putDoubles(104, pixdim, 8);
        const std::int64_t offset = std::max<std::int64_t>(544, std::int64_t(voxOffset) + 192);
        put(168, &offset, 8);
        putDoubles(176, &sclSlope, 1);
        putDoubles(184, &sclInter, 1);
        const std::int32_t q = qformCode, sf = sformCode;
        put(344, &q, 4);
        put(348, &sf, 4);
        putDoubles(352, quatern, 3);
        putDoubles(376, qoffset, 3);
        putDoubles(400, srow[0], 4);
        putDoubles(432, srow[1], 4);
        putDoubles(464, srow[2], 4);
        return h;
    }
};

/// Two reads of the same volume: grid, type, geometry, scaling and bytes.
inline void expectSameVolume(const Volume& a, const Volume& b) {
    EXPECT_EQ(a.dims, b.dims);
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.spacing, b.spacing);
    EXPECT_EQ(a.direction, b.direction);
    EXPECT_EQ(a.origin, b.origin);
    EXPECT_EQ(a.space, b.space);
    EXPECT_EQ(a.slope, b.slope);
    EXPECT_EQ(a.inter, b.inter);
    EXPECT_TRUE(a.data == b.data);
}

/// The message of the InputError that `f` throws ("" when none is thrown).
template <typename F>
std::string inputError(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

} // namespace cutaway::test
