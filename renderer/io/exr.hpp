#pragma once
// OpenEXR output: RGBA, linear, premultiplied (EXR's own convention), half by
// default or 32-bit float on request, ZIP compression, written atomically.
// String attributes go into the header (frame number, scene, version).
#include "io/image.hpp"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace cutaway {

struct ExrOptions {
    bool halfFloat = true;
    std::vector<std::pair<std::string, std::string>> attributes; ///< extra string attributes
};

void writeExr(const std::filesystem::path& path, const Image& image,
              const ExrOptions& options = {});

/// Reads the R, G, B, A channels of an EXR (any pixel type) into an Image.
/// Missing channels read as 0 (alpha as 1). Throws InputError on failure.
Image readExr(const std::filesystem::path& path);

/// Reads one string attribute; empty when absent.
std::string readExrStringAttribute(const std::filesystem::path& path, const std::string& name);

} // namespace cutaway
