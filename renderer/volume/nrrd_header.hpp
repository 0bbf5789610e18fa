#pragma once
// Private helper: the text side of a NRRD header. Errors name `ctx` (the file).
#include "volume/volume.hpp"

#include <cstddef>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cutaway::detail {

/// The raw text of the fields cutaway uses; unknown fields are skipped.
struct NrrdFields {
    std::optional<std::string> type, dimension, sizes, endian, encoding, spacings, space,
        spaceDimension, directions, origin, dataFile, byteSkip, lineSkip, slope, inter;
};

/// Reads the magic line and the fields up to the first blank line (or the end
/// of the file, for a detached header); `endedByBlankLine` tells which.
NrrdFields readNrrdHeader(std::istream& in, const std::string& ctx, bool& endedByBlankLine);

/// Reads one line without its "\n" / "\r\n"; false at the end of the stream.
/// Each byte read counts against `budget`; running out is an error.
bool readNrrdLine(std::istream& in, std::string& line, std::size_t& budget, const std::string& ctx);

std::vector<std::string_view> splitWords(std::string_view text);

/// Any NRRD spelling of a supported type ("unsigned short int", "uint16_t", ...).
VoxelType parseNrrdType(std::string_view text, const std::string& ctx);

/// "(a,b,c)" vectors and "none" entries, as in `space directions` and `space origin`.
std::vector<std::optional<std::vector<double>>>
parseNrrdVectors(std::string_view text, const char* field, const std::string& ctx);

} // namespace cutaway::detail
