#pragma once
// OpenEXR output: RGBA, linear, premultiplied (EXR's own convention), half by
// default or 32-bit float on request, ZIP compression by default (any of
// OpenEXR's lossless ones on request), written atomically.
// String attributes go into the header (frame number, scene, version).
#include "io/image.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cutaway {

/// A channel beyond RGBA: one 32-bit float per pixel, rows as in Image.
struct ExrChannel {
    std::string name;
    const std::vector<float>* values = nullptr;
};

/// OpenEXR's lossless compressions (the lossy ones are left out: an
/// illustration's pixels go on to be composited and measured).
enum class ExrCompression {
    None, ///< uncompressed: the fastest to write, the largest
    Rle,  ///< run lengths: fast, small only for flat areas
    Zips, ///< zlib, one scanline at a time
    Zip,  ///< zlib, 16 scanlines at a time: the default
    Piz   ///< wavelets: often the smallest for noisy images, slower
};

struct ExrOptions {
    bool halfFloat = true;
    ExrCompression compression = ExrCompression::Zip;
    std::vector<std::pair<std::string, std::string>> attributes; ///< extra string attributes
    std::vector<ExrChannel> channels; ///< extra FLOAT channels (e.g. operator ids)
    /// OpenEXR's standard framesPerSecond attribute (a rational), which
    /// compositors (Nuke, DaVinci Resolve) read; none when not set.
    std::optional<double> framesPerSecond;
};

void writeExr(const std::filesystem::path& path, const Image& image,
              const ExrOptions& options = {});

/// Reads the R, G, B, A channels of an EXR (any pixel type) into an Image.
/// Missing channels read as 0 (alpha as 1). Throws InputError on failure.
Image readExr(const std::filesystem::path& path);

/// Reads one channel as floats (row 0 at the top); throws InputError when absent.
std::vector<float> readExrChannel(const std::filesystem::path& path, const std::string& name);

/// Reads one string attribute; empty when absent.
std::string readExrStringAttribute(const std::filesystem::path& path, const std::string& name);

} // namespace cutaway
