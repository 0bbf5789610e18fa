#include "io/exr.hpp"

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/halves.hpp"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRational.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <memory>
#include <new>
#include <numeric>

namespace cutaway {

namespace {

namespace fs = std::filesystem;

constexpr const char* kChannelNames[4] = {"R", "G", "B", "A"};
void checkImage(const fs::path& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
        throw RuntimeError("cannot write " + path.string() + ": image is " +
                           std::to_string(image.width) + "x" + std::to_string(image.height) +
                           " but holds " + std::to_string(image.rgba.size()) + " floats");
    }
}

Imf::Compression toImf(ExrCompression compression) {
    switch (compression) {
    case ExrCompression::None:
        return Imf::NO_COMPRESSION;
    case ExrCompression::Rle:
        return Imf::RLE_COMPRESSION;
    case ExrCompression::Zips:
        return Imf::ZIPS_COMPRESSION;
    case ExrCompression::Zip:
        return Imf::ZIP_COMPRESSION;
    case ExrCompression::Piz:
        return Imf::PIZ_COMPRESSION;
    }
    return Imf::ZIP_COMPRESSION;
}

// A frame rate as OpenEXR's rational: the NTSC rates exactly (30000/1001),
// others to a thousandth of a frame per second.
Imf::Rational frameRate(double fps) {
    for (const int base : {24, 30, 60}) {
        const double ntsc = base * 1000.0 / 1001.0;
        if (std::abs(fps - ntsc) < 1e-3) return Imf::Rational(base * 1000, 1001);
    }
    const double thousandths = std::round(fps * 1000.0);
    const int gcd = std::gcd(static_cast<int>(thousandths), 1000);
    return Imf::Rational(static_cast<int>(thousandths) / gcd, static_cast<unsigned>(1000 / gcd));
}

Imf::Header makeHeader(const Image& image, const ExrOptions& options) {
    Imf::Header header(image.width, image.height); // data = display window, origin (0,0)
    header.compression() = toImf(options.compression);
    header.lineOrder() = Imf::INCREASING_Y; // row 0 first, the top row as in Image
    const Imf::PixelType type = options.halfFloat ? Imf::HALF : Imf::FLOAT;
    for (const char* name : kChannelNames)
        header.channels().insert(name, Imf::Channel(type));
    for (const ExrChannel& extra : options.channels)
        header.channels().insert(extra.name, Imf::Channel(Imf::FLOAT));
    // "software" is not one of OpenEXR's standard attributes; it is a plain
    // string attribute by convention. Inserted first so a caller's attribute
    // of the same name wins.
    header.insert("software", Imf::StringAttribute("cutaway " CUTAWAY_VERSION));
    if (options.framesPerSecond)
        Imf::addFramesPerSecond(header, frameRate(*options.framesPerSecond));
    for (const auto& [name, value] : options.attributes) {
        header.insert(name, Imf::StringAttribute(value)); // throws on a clash of types
    }
    return header;
}

// Rows handed to OpenEXR at a time: a multiple of the scan lines of a ZIP
// (16) and a PIZ (32) block. Half floats are converted a strip at a time,
// into a buffer that stays in cache and in the heap: a whole 1920x1080
// frame's copy (16 MB) was mapped afresh and faulted in for every frame.
constexpr int kExrStripRows = 32;

// Writes through our own ofstream: OutputFile's destructor writes the line
// offset table and swallows any error doing so, so the stream state is the
// only reliable sign that the file is complete.
void writePixels(const fs::path& tmp, const Imf::Header& header, const Image& image, bool halfFloat,
                 const std::vector<ExrChannel>& extra) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw RuntimeError("cannot create " + tmp.string());
    {
        Imf::StdOFStream stream(out, tmp.c_str());
        Imf::OutputFile file(stream, header);
        const auto width = static_cast<std::size_t>(image.width);
        const std::size_t stripValues = width * 4 * std::min(kExrStripRows, image.height);
        const auto strip = std::make_unique_for_overwrite<half[]>(halfFloat ? stripValues : 0);
        for (int first = 0; first < image.height; first += kExrStripRows) {
            const int rows = std::min(kExrStripRows, image.height - first);
            const Imath::Box2i box({0, first}, {image.width - 1, first + rows - 1});
            const float* values = image.rgba.data() + width * 4 * first;
            Imf::FrameBuffer frameBuffer;
            for (int c = 0; c < 4; ++c) {
                frameBuffer.insert(
                    kChannelNames[c],
                    halfFloat ? Imf::Slice::Make(Imf::HALF, strip.get() + c, box, 4 * sizeof(half),
                                                 4 * sizeof(half) * width)
                              : Imf::Slice::Make(Imf::FLOAT, values + c, box, 4 * sizeof(float),
                                                 4 * sizeof(float) * width));
            }
            for (const ExrChannel& channel : extra) {
                frameBuffer.insert(channel.name,
                                   Imf::Slice::Make(Imf::FLOAT, channel.values->data(),
                                                    header.dataWindow(), sizeof(float),
                                                    sizeof(float) * width));
            }
            if (halfFloat) toHalves(values, strip.get(), width * 4 * rows);
            file.setFrameBuffer(frameBuffer);
            file.writePixels(rows);
        }
    }
    errno = 0;
    out.close(); // the last buffered bytes go out here, and may not fit
    if (!out)
        throw RuntimeError(std::string("write error: ") +
                           (errno ? std::strerror(errno) : "the stream failed (disk full?)"));
}

} // namespace

void writeExr(const fs::path& path, const Image& image, const ExrOptions& options) {
    checkImage(path, image);
    for (const ExrChannel& channel : options.channels) {
        if (!channel.values || channel.values->size() != image.rgba.size() / 4)
            throw RuntimeError("cannot write " + path.string() + ": channel " + channel.name +
                               " does not have one value per pixel");
    }
    writeAtomically(path, [&](const fs::path& tmp) {
        try {
            const Imf::Header header = makeHeader(image, options);
            writePixels(tmp, header, image, options.halfFloat, options.channels);
        } catch (const std::exception& e) { // ours, and Iex::BaseExc which derives from it
            throw RuntimeError("cannot write " + path.string() + ": " + e.what());
        }
    });
}

Image readExr(const fs::path& path) {
    Image image;
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
        const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
        // Bounds the allocation below; 2^28 pixels is 4 GiB of floats.
        if (width <= 0 || height <= 0 || width > std::numeric_limits<int>::max() ||
            height > std::numeric_limits<int>::max() || width * height > (std::int64_t{1} << 28)) {
            throw InputError("cannot read " + path.string() + ": unsupported data window " +
                             std::to_string(width) + "x" + std::to_string(height));
        }
        image = Image(static_cast<int>(width), static_cast<int>(height));

        // The file's channels (HALF, FLOAT or UINT) are converted to float by
        // OpenEXR; a channel absent from the file is filled with fillValue.
        const std::size_t xStride = 4 * sizeof(float);
        const std::size_t yStride = xStride * static_cast<std::size_t>(width);
        Imf::FrameBuffer frameBuffer;
        for (int c = 0; c < 4; ++c) {
            const double fill = c == 3 ? 1.0 : 0.0;
            frameBuffer.insert(kChannelNames[c],
                               Imf::Slice::Make(Imf::FLOAT, image.rgba.data() + c, window, xStride,
                                                yStride, 1, 1, fill));
        }
        file.setFrameBuffer(frameBuffer);
        file.readPixels(window.min.y, window.max.y);
    } catch (const InputError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw InputError("cannot read " + path.string() + ": image too large for memory");
    } catch (const std::exception& e) {
        throw InputError("cannot read EXR " + path.string() + ": " + e.what());
    }
    return image;
}

std::string readExrStringAttribute(const fs::path& path, const std::string& name) {
    try {
        // Opening reads the header and the offset table only, not the pixels.
        Imf::InputFile file(path.c_str());
        const auto* attribute = file.header().findTypedAttribute<Imf::StringAttribute>(name);
        return attribute ? attribute->value() : std::string();
    } catch (const std::exception& e) {
        throw InputError("cannot read EXR " + path.string() + ": " + e.what());
    }
}

} // namespace cutaway

namespace cutaway {

std::vector<float> readExrChannel(const fs::path& path, const std::string& name) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        if (!file.header().channels().findChannel(name))
            throw InputError("cannot read " + path.string() + ": no channel " + name);
        const std::size_t width = static_cast<std::size_t>(window.max.x - window.min.x + 1);
        const std::size_t height = static_cast<std::size_t>(window.max.y - window.min.y + 1);
        std::vector<float> values(width * height);
        Imf::FrameBuffer frameBuffer;
        frameBuffer.insert(name, Imf::Slice::Make(Imf::FLOAT, values.data(), window, sizeof(float),
                                                  sizeof(float) * width));
        file.setFrameBuffer(frameBuffer);
        file.readPixels(window.min.y, window.max.y);
        return values;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError("cannot read EXR " + path.string() + ": " + e.what());
    }
}

} // namespace cutaway
