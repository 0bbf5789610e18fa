#include "io/png.hpp"

#include "core/error.hpp"
#include "io/atomic_file.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>
#include <zlib.h>

namespace cutaway {

namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

// IDAT payloads are split so each chunk stays far below PNG's 2^31-1 chunk
// limit and zlib's 32-bit crc32() length.
constexpr std::size_t kIdatChunkBytes = 1u << 20;

void appendU32(Bytes& out, std::uint32_t v) { // PNG integers are big-endian
    out.push_back(static_cast<std::uint8_t>(v >> 24));
    out.push_back(static_cast<std::uint8_t>(v >> 16));
    out.push_back(static_cast<std::uint8_t>(v >> 8));
    out.push_back(static_cast<std::uint8_t>(v));
}

// length, type, data, CRC-32 over type and data.
void appendChunk(Bytes& out, const char type[4], const std::uint8_t* data, std::size_t size) {
    appendU32(out, static_cast<std::uint32_t>(size));
    const std::size_t typeAt = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data, data + size);
    const uLong crc = crc32(0L, out.data() + typeAt, static_cast<uInt>(size + 4));
    appendU32(out, static_cast<std::uint32_t>(crc));
}

void appendChunk(Bytes& out, const char type[4], const Bytes& data) {
    appendChunk(out, type, data.data(), data.size());
}

// [0,1] -> 0..255, NaN -> 0.
std::uint8_t toByte(float v) {
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 255;
    return static_cast<std::uint8_t>(std::lround(v * 255.0f));
}

std::uint32_t bitsOf(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return bits;
}

float floatOf(std::uint32_t bits) {
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

// toByte(linearToSrgb(x)) without a pow per channel: the byte only grows with
// x, so it is fixed by the smallest x of each byte (`first`, found once by
// bisection over the floats of [0, 1], whose bit patterns grow with them); a
// bucket of 1/kBuckets of the linear range starts from its lower edge's byte
// and steps past the thresholds in it (at most two: the curve rises at most
// 3300 bytes per unit).
class SrgbBytes {
public:
    SrgbBytes() {
        auto exact = [](float x) { return toByte(linearToSrgb(x)); };
        m_first[0] = 0.0f;
        for (int b = 1; b < 256; ++b) {
            std::uint32_t below = 0, at = bitsOf(1.0f); // exact(below) < b <= exact(at)
            while (at - below > 1) {
                const std::uint32_t mid = below + (at - below) / 2;
                (exact(floatOf(mid)) >= b ? at : below) = mid;
            }
            m_first[b] = floatOf(at);
        }
        for (int i = 0; i < kBuckets; ++i)
            m_bucket[i] = exact(static_cast<float>(i) / kBuckets);
    }
    std::uint8_t operator()(float x) const {
        if (!(x > 0.0f)) return 0; // also NaN
        if (x >= 1.0f) return 255;
        int b = m_bucket[std::min(static_cast<int>(x * kBuckets), kBuckets - 1)];
        while (b < 255 && x >= m_first[b + 1])
            ++b;
        return static_cast<std::uint8_t>(b);
    }

private:
    static constexpr int kBuckets = 4096;
    std::array<float, 256> m_first{};
    std::array<std::uint8_t, kBuckets> m_bucket{};
};

const SrgbBytes& srgbBytes() {
    static const SrgbBytes table;
    return table;
}

// Linear premultiplied RGBA -> 8-bit straight (un-premultiplied) sRGB colour
// with linear alpha, as PNG defines it.
void encodePixel(const SrgbBytes& srgb, const float* in, std::uint8_t* out) {
    float a = in[3];
    if (!(a > 0.0f)) a = 0.0f; // also NaN
    a = std::min(a, 1.0f);
    for (int c = 0; c < 3; ++c)
        out[c] = srgb(a > 0.0f ? in[c] / a : 0.0f);
    out[3] = toByte(a);
}

int paeth(int a, int b, int c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

int absResidual(int value, int predictor) {
    return std::abs(static_cast<std::int8_t>(static_cast<std::uint8_t>(value - predictor)));
}

constexpr std::size_t kBpp = 4; // bytes per pixel: 8-bit RGBA

// The residuals of one scanline under PNG filter `Filter`, into `out` (n bytes).
// One loop per filter, so that each is a straight loop the compiler can
// vectorize.
template <int Filter>
void applyFilter(const std::uint8_t* row, const std::uint8_t* prev, std::size_t n,
                 std::uint8_t* out) {
    for (std::size_t i = kBpp; i < n + kBpp; ++i) {
        const int left = row[i - kBpp], up = prev[i];
        int predictor = 0;
        if constexpr (Filter == 1) predictor = left;
        if constexpr (Filter == 2) predictor = up;
        if constexpr (Filter == 3) predictor = (left + up) / 2;
        if constexpr (Filter == 4) predictor = paeth(left, up, prev[i - kBpp]);
        out[i - kBpp] = static_cast<std::uint8_t>(row[i] - predictor);
    }
}

// Filters one scanline with the PNG filter (of the five) whose residuals have
// the smallest sum of absolute (signed) values, the heuristic the PNG spec
// recommends; it compresses smooth renders far better than filter 0 alone.
// `row` and `prev` (the previous raw row, zero above the first) each start
// with kBpp zero bytes, the "left" of the first pixel; n bytes follow. One
// pass sums all five filters' costs, a second writes the chosen one's filter
// byte and residuals to `out` (n + 1 bytes).
void filterRow(const std::uint8_t* row, const std::uint8_t* prev, std::size_t n,
               std::uint8_t* out) {
    std::array<std::uint32_t, 5> cost{};
    for (std::size_t i = kBpp; i < n + kBpp; ++i) {
        const int x = row[i], left = row[i - kBpp], up = prev[i], upLeft = prev[i - kBpp];
        cost[0] += absResidual(x, 0);
        cost[1] += absResidual(x, left);
        cost[2] += absResidual(x, up);
        cost[3] += absResidual(x, (left + up) / 2);
        cost[4] += absResidual(x, paeth(left, up, upLeft));
    }
    const auto best = static_cast<int>(std::min_element(cost.begin(), cost.end()) - cost.begin());
    out[0] = static_cast<std::uint8_t>(best);
    switch (best) {
    case 0:
        return applyFilter<0>(row, prev, n, out + 1);
    case 1:
        return applyFilter<1>(row, prev, n, out + 1);
    case 2:
        return applyFilter<2>(row, prev, n, out + 1);
    case 3:
        return applyFilter<3>(row, prev, n, out + 1);
    default:
        return applyFilter<4>(row, prev, n, out + 1);
    }
}

// Deflates a frame's filtered rows as they are made, a strip at a time, so
// no buffer holds them all: a 1920x1080 frame's filtered bytes and their
// compressed copy (8 MB each) were mapped afresh and faulted in for every
// frame. The fastest level: a preview is written per frame while the next
// one renders on the same cores (at 512x512, 27 -> 13 ms, files 21 % larger).
class Deflater {
public:
    explicit Deflater(const fs::path& path) : m_path(path) {
        if (deflateInit(&m_stream, Z_BEST_SPEED) != Z_OK) fail("deflateInit", Z_STREAM_ERROR);
    }
    ~Deflater() { deflateEnd(&m_stream); }
    Deflater(const Deflater&) = delete;
    Deflater& operator=(const Deflater&) = delete;

    /// Adds `size` bytes; `last` finishes the stream.
    void add(const std::uint8_t* bytes, std::size_t size, bool last) {
        m_stream.next_in = const_cast<Bytef*>(bytes); // zlib's API predates const
        m_stream.avail_in = static_cast<uInt>(size);
        const int flush = last ? Z_FINISH : Z_NO_FLUSH;
        for (;;) {
            std::array<std::uint8_t, 1 << 16> chunk;
            m_stream.next_out = chunk.data();
            m_stream.avail_out = static_cast<uInt>(chunk.size());
            const int status = deflate(&m_stream, flush);
            if (status == Z_STREAM_ERROR) fail("deflate", status);
            m_out.insert(m_out.end(), chunk.data(), m_stream.next_out);
            if (last ? status == Z_STREAM_END : m_stream.avail_out != 0) return;
        }
    }
    const Bytes& out() const { return m_out; }

private:
    [[noreturn]] void fail(const char* what, int status) const {
        throw RuntimeError("cannot write " + m_path.string() + ": zlib " + what + " failed (" +
                           std::to_string(status) + ")");
    }

    const fs::path& m_path;
    z_stream m_stream{};
    Bytes m_out;
};

// Rows filtered before each call to deflate.
constexpr std::size_t kPngStripRows = 32;

Bytes encodePng(const fs::path& path, const Image& image) {
    const auto width = static_cast<std::size_t>(image.width);
    const auto height = static_cast<std::size_t>(image.height);
    const std::size_t rowBytes = width * 4;

    const SrgbBytes& srgb = srgbBytes();
    // Left uninitialized: every byte of a strip is written before it is read.
    const auto strip =
        std::make_unique_for_overwrite<std::uint8_t[]>((rowBytes + 1) * kPngStripRows);
    Bytes row(kBpp + rowBytes, 0), prev(kBpp + rowBytes, 0);
    Deflater deflater(path);
    for (std::size_t first = 0; first < height; first += kPngStripRows) {
        const std::size_t rows = std::min(kPngStripRows, height - first);
        for (std::size_t r = 0; r < rows; ++r) {
            const float* src = image.rgba.data() + (first + r) * rowBytes;
            for (std::size_t x = 0; x < width; ++x)
                encodePixel(srgb, src + x * 4, row.data() + kBpp + x * 4);
            filterRow(row.data(), prev.data(), rowBytes, strip.get() + r * (rowBytes + 1));
            std::swap(row, prev);
        }
        deflater.add(strip.get(), rows * (rowBytes + 1), first + rows == height);
    }
    const Bytes& compressed = deflater.out();
    const std::size_t compressedSize = compressed.size();

    Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    // Each IDAT adds 12 bytes; the signature and the other chunks under 128.
    png.reserve(compressedSize + 12 * (compressedSize / kIdatChunkBytes + 1) + 128);
    Bytes ihdr;
    appendU32(ihdr, static_cast<std::uint32_t>(image.width));
    appendU32(ihdr, static_cast<std::uint32_t>(image.height));
    ihdr.insert(ihdr.end(), {8, 6, 0, 0, 0}); // 8 bit, RGBA, deflate, adaptive, no interlace
    appendChunk(png, "IHDR", ihdr);
    appendChunk(png, "sRGB", Bytes{0}); // rendering intent 0: perceptual
    // gAMA and cHRM matching sRGB, for decoders that ignore sRGB (PNG spec 11.3.3.5).
    Bytes gama;
    appendU32(gama, 45455);
    appendChunk(png, "gAMA", gama);
    Bytes chrm;
    for (std::uint32_t v : {31270u, 32900u, 64000u, 33000u, 30000u, 60000u, 15000u, 6000u}) {
        appendU32(chrm, v);
    }
    appendChunk(png, "cHRM", chrm);
    for (std::size_t at = 0; at < compressedSize; at += kIdatChunkBytes) {
        const std::size_t size = std::min<std::size_t>(kIdatChunkBytes, compressedSize - at);
        appendChunk(png, "IDAT", compressed.data() + at, size);
    }
    appendChunk(png, "IEND", nullptr, 0);
    return png;
}

} // namespace

float linearToSrgb(float linear) {
    if (!(linear > 0.0f)) return 0.0f; // also NaN
    if (linear >= 1.0f) return 1.0f;
    if (linear <= 0.0031308f) return 12.92f * linear;
    return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t linearToSrgbByte(float linear) {
    return srgbBytes()(linear);
}

void writePng(const fs::path& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
        throw RuntimeError("cannot write " + path.string() + ": image is " +
                           std::to_string(image.width) + "x" + std::to_string(image.height) +
                           " but holds " + std::to_string(image.rgba.size()) + " floats");
    }
    const Bytes png = encodePng(path, image);
    writeAtomically(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (out) {
            out.write(reinterpret_cast<const char*>(png.data()),
                      static_cast<std::streamsize>(png.size()));
            out.close();
        }
        if (!out) {
            const int err = errno;
            throw RuntimeError("cannot write " + path.string() + " (" + std::strerror(err) + ")");
        }
    });
}

} // namespace cutaway
