#pragma once
// The compression an EXR file's header names, read from its bytes (not
// through OpenEXR, which the library under test uses to write it): the value
// of the attribute "compression" of type "compression", OpenEXR's code (0 none,
// 1 RLE, 2 ZIPS, 3 ZIP, 4 PIZ); -1 when the file has no such attribute.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

namespace cutaway::test {

inline int exrCompressionCode(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // name, NUL, type, NUL, a 4-byte little-endian size of 1, the value.
    static const std::string kAttribute("compression\0compression\0\1\0\0\0", 28);
    const std::size_t at = bytes.find(kAttribute);
    if (at == std::string::npos || at + kAttribute.size() >= bytes.size()) return -1;
    return static_cast<unsigned char>(bytes[at + kAttribute.size()]);
}

/// The standard attribute framesPerSecond (type "rational": a 4-byte signed
/// numerator, a 4-byte unsigned denominator, little-endian) as {n, d}; {0, 0}
/// when the file has none.
inline std::pair<int, unsigned> exrFramesPerSecond(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    static const std::string kAttribute("framesPerSecond\0rational\0\x08\0\0\0", 29);
    const std::size_t at = bytes.find(kAttribute);
    if (at == std::string::npos || at + kAttribute.size() + 8 > bytes.size()) return {0, 0};
    const auto word = [&](std::size_t offset) {
        std::uint32_t v = 0;
        for (int b = 3; b >= 0; --b)
            v = (v << 8) | static_cast<unsigned char>(bytes[at + kAttribute.size() + offset + b]);
        return v;
    };
    return {static_cast<int>(word(0)), word(4)};
}

} // namespace cutaway::test
