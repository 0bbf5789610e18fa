#include "io/png.hpp"

#include "core/error.hpp"
#include "io/atomic_file.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <png.h>
#include <string>
#include <utility>
#include <vector>
#include <zlib.h>

namespace cutaway {

namespace {

namespace fs = std::filesystem;

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

constexpr std::size_t kBpp = 4; // bytes per pixel: 8-bit RGBA

int paeth(int a, int b, int c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

int absResidual(int value, int predictor) {
    return std::abs(static_cast<std::int8_t>(static_cast<std::uint8_t>(value - predictor)));
}

// The filter libpng's search picks for a row: of the five, the one whose
// residuals have the least sum of absolute (signed) values, the lower type
// on a tie. Found here in one pass that sums all five costs and that the
// compiler vectorizes; libpng's own search makes a pass per filter (each
// stopping once it is worse) and made a 1920x1080 write about 1.5 times
// slower.
// `row` and `prev` (the previous row, zero above the first) each start with
// kBpp zero bytes, the "left" of the first pixel; n bytes follow.
int leastCostFilter(const std::uint8_t* row, const std::uint8_t* prev, std::size_t n) {
    std::array<std::uint32_t, 5> cost{};
    for (std::size_t i = kBpp; i < n + kBpp; ++i) {
        const int x = row[i], left = row[i - kBpp], up = prev[i], upLeft = prev[i - kBpp];
        cost[0] += absResidual(x, 0);
        cost[1] += absResidual(x, left);
        cost[2] += absResidual(x, up);
        cost[3] += absResidual(x, (left + up) / 2);
        cost[4] += absResidual(x, paeth(left, up, upLeft));
    }
    return static_cast<int>(std::min_element(cost.begin(), cost.end()) - cost.begin());
}

// Whether leastCostFilter() picks the rows' filters. Not for images one
// pixel high or wide, for which libpng leaves out the filters that need the
// missing neighbours, nor for rows so long that a cost could pass 2^32 (a
// byte adds at most 128): libpng's search, the same heuristic, does those.
bool choosesFilters(const Image& image) {
    const auto rowBytes = static_cast<std::uint64_t>(image.width) * kBpp;
    return image.width > 1 && image.height > 1 && rowBytes * 128 < (std::uint64_t{1} << 32);
}

// What libpng's callbacks share with writePng. Plain data: a libpng error
// longjmps out of the callbacks, past frames that must hold nothing to destroy.
struct PngSink {
    std::ofstream* out = nullptr;
    int writeErrno = 0;     ///< errno of the write that failed; 0 when none did
    char message[256] = {}; ///< libpng's message for any other failure
};

// libpng's error handler must not return: it keeps the message for the
// exception writePng throws and jumps back to the setjmp in encodeGuarded().
[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
    auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
    std::snprintf(sink->message, sizeof sink->message, "%s", message);
    png_longjmp(png, 1);
}

// libpng warns of settings it had to adjust; the ones here are fixed and
// valid, and the default handler would print to stderr amid the CLI's report.
void onPngWarning(png_structp, png_const_charp) {}

// The file is written as libpng makes it: a full disk fails here, keeping
// errno for the message, and stops libpng.
void onPngWrite(png_structp png, png_bytep data, std::size_t size) {
    auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
    sink->out->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!*sink->out) {
        sink->writeErrno = errno;
        png_error(png, "writing failed");
    }
}

// Nothing to do: the stream is flushed, and checked, when it is closed.
void onPngFlush(png_structp) {}

// IDAT chunks (and libpng's compressed-data buffer) of 1 MiB rather than
// libpng's 8 KiB: fewer chunk headers and CRCs in an HD frame.
constexpr std::size_t kIdatChunkBytes = 1u << 20;

// The encoding, fixed so that an image always gives the same bytes.
void configure(png_structp png, png_infop info, const Image& image) {
    // Any size PNG allows, not just libpng's default of a million pixels a side.
    png_set_user_limits(png, PNG_UINT_31_MAX, PNG_UINT_31_MAX);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB_ALPHA,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
    // Each row takes the filter of the five whose residuals have the least
    // sum of absolute (signed) values, the heuristic the PNG spec recommends;
    // it compresses smooth renders far better than filter 0 alone. libpng
    // searches for it in the first row (and where choosesFilters() says no),
    // encode() in the others.
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
    // The fastest level: a preview is written per frame while the next one
    // renders on the same cores (at 512x512, 27 -> 13 ms, files 21 % larger).
    // zlib's own defaults otherwise (libpng's strategy for filtered rows is
    // Z_FILTERED), so the compressed stream depends on zlib alone.
    png_set_compression_level(png, Z_BEST_SPEED);
    png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
    png_set_compression_mem_level(png, 8);
    png_set_compression_window_bits(png, 15);
    png_set_compression_buffer_size(png, kIdatChunkBytes);
}

// sRGB (rendering intent 0, perceptual), then gAMA and cHRM matching it for
// decoders that ignore sRGB (PNG spec 11.3.3.5). Written by hand because
// png_set_sRGB_gAMA_and_cHRM() puts gAMA first, which would change the bytes
// of every preview cutaway has written.
void writeColourChunks(png_structp png) {
    const png_byte intent = 0;
    png_write_chunk(png, reinterpret_cast<png_const_bytep>("sRGB"), &intent, 1);
    std::array<png_byte, 4> gama{};
    png_save_uint_32(gama.data(), 45455);
    png_write_chunk(png, reinterpret_cast<png_const_bytep>("gAMA"), gama.data(), gama.size());
    constexpr std::array<png_uint_32, 8> kChrm = {31270, 32900, 64000, 33000,
                                                  30000, 60000, 15000, 6000};
    std::array<png_byte, 4 * kChrm.size()> chrm{};
    for (std::size_t i = 0; i < kChrm.size(); ++i)
        png_save_uint_32(chrm.data() + 4 * i, kChrm[i]);
    png_write_chunk(png, reinterpret_cast<png_const_bytep>("cHRM"), chrm.data(), chrm.size());
}

// The whole file, one row at a time: libpng filters each row as it comes and
// deflates it straight into the file, so no buffer holds the frame. `rows`
// holds two rows of kBpp zero bytes and then width * 4 bytes of 8-bit RGBA,
// the second zero: this row and the one above. Any libpng call here may
// longjmp.
void encode(png_structp png, png_infop info, const Image& image, std::uint8_t* rows) {
    configure(png, info, image);
    png_write_info(png, info);
    writeColourChunks(png);
    const SrgbBytes& srgb = srgbBytes();
    const auto width = static_cast<std::size_t>(image.width);
    const std::size_t rowBytes = width * kBpp;
    const bool chooses = choosesFilters(image);
    std::uint8_t* row = rows;
    std::uint8_t* prev = rows + kBpp + rowBytes;
    for (std::size_t y = 0; y < static_cast<std::size_t>(image.height); ++y) {
        const float* src = image.rgba.data() + y * width * 4;
        for (std::size_t x = 0; x < width; ++x)
            encodePixel(srgb, src + x * 4, row + kBpp + x * kBpp);
        // From the second row: libpng sets up the filters' buffers with the
        // first, for the filters set then, so all five must be set then.
        if (chooses && y > 0) {
            constexpr std::array<int, 5> kAlone = {PNG_FILTER_NONE, PNG_FILTER_SUB, PNG_FILTER_UP,
                                                   PNG_FILTER_AVG, PNG_FILTER_PAETH};
            png_set_filter(png, PNG_FILTER_TYPE_BASE, kAlone[leastCostFilter(row, prev, rowBytes)]);
        }
        png_write_row(png, row + kBpp);
        std::swap(row, prev);
    }
    png_write_end(png, nullptr);
}

// The one setjmp: false after a libpng error, whose cause is in the sink.
// longjmp skips destructors, so neither this frame nor any between it and
// libpng holds an object that has one (encode's locals are plain).
bool encodeGuarded(png_structp png, png_infop info, const Image& image, std::uint8_t* rows) {
    if (setjmp(png_jmpbuf(png))) return false;
    encode(png, info, image, rows);
    return true;
}

// libpng's write and info structs, destroyed however the write ends.
class PngWriter {
public:
    PngWriter(const fs::path& path, PngSink& sink) {
        m_png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, onPngError, onPngWarning);
        if (m_png != nullptr) m_info = png_create_info_struct(m_png);
        if (m_info == nullptr) {
            png_destroy_write_struct(&m_png, nullptr);
            throw RuntimeError("cannot write " + path.string() + ": libpng could not start");
        }
        png_set_write_fn(m_png, &sink, onPngWrite, onPngFlush);
    }
    ~PngWriter() { png_destroy_write_struct(&m_png, &m_info); }
    PngWriter(const PngWriter&) = delete;
    PngWriter& operator=(const PngWriter&) = delete;

    png_structp png() const { return m_png; }
    png_infop info() const { return m_info; }

private:
    png_structp m_png = nullptr;
    png_infop m_info = nullptr;
};

// Encodes `image` into the file `tmp` (the temporary of `path`).
void writePngFile(const fs::path& path, const fs::path& tmp, const Image& image) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    PngSink sink;
    sink.out = &out;
    if (out) {
        std::vector<std::uint8_t> rows(2 * (kBpp + static_cast<std::size_t>(image.width) * kBpp));
        const PngWriter writer(path, sink);
        if (!encodeGuarded(writer.png(), writer.info(), image, rows.data()) && sink.writeErrno == 0)
            throw RuntimeError("cannot write " + path.string() + ": libpng: " + sink.message);
        out.close();
    }
    if (!out) {
        const int err = sink.writeErrno != 0 ? sink.writeErrno : errno;
        throw RuntimeError("cannot write " + path.string() + " (" + std::strerror(err) + ")");
    }
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
    writeAtomically(path, [&](const fs::path& tmp) { writePngFile(path, tmp, image); });
}

} // namespace cutaway
