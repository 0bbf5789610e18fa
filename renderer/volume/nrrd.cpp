// NRRD reader (http://teem.sourceforge.net/nrrd/format.html), NRRD0001..NRRD0005:
// attached (.nrrd) and detached (.nhdr + data file) headers, raw and gzip
// encodings, either byte order, 3D grids (or 4D with a first axis of size 1).
#include <cctype>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/error.hpp"
#include "volume/byte_order.hpp"
#include "volume/gzip.hpp"
#include "volume/io_util.hpp"
#include "volume/volume.hpp"

namespace cutaway {

namespace {

using detail::toLower;
using detail::trim;

/// A header longer than this is not a header (a binary file without the blank line).
constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

struct NrrdFields {
    std::optional<std::string> type, dimension, sizes, endian, encoding, spacings, directions,
        origin, dataFile, byteSkip, lineSkip, slope, inter;
};

std::vector<std::string_view> splitWords(std::string_view text) {
    std::vector<std::string_view> words;
    text = trim(text);
    while (!text.empty()) {
        std::size_t end = 0;
        while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
        words.push_back(text.substr(0, end));
        text = trim(text.substr(end));
    }
    return words;
}

/// Reads one line (without "\n" or "\r\n"); false at the end of the stream.
bool readLine(std::istream& in, std::string& line, std::size_t& budget, const std::string& ctx) {
    line.clear();
    std::streambuf* buffer = in.rdbuf();
    bool any = false;
    for (;;) {
        const int c = buffer->sbumpc();
        if (c == std::char_traits<char>::eof()) break;
        any = true;
        if (budget-- == 0) {
            throw InputError(ctx + ": header longer than 1 MiB (is the blank line that ends it "
                                   "missing?)");
        }
        if (c == '\n') break;
        line.push_back(static_cast<char>(c));
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return any;
}

VoxelType parseNrrdType(std::string_view text, const std::string& ctx) {
    // Collapse whitespace so "unsigned   short" is "unsigned short".
    std::string name;
    for (std::string_view word : splitWords(text)) {
        if (!name.empty()) name += ' ';
        name += toLower(word);
    }
    struct Spelling {
        const char* name;
        VoxelType type;
    };
    static constexpr Spelling kSpellings[] = {
        {"signed char", VoxelType::I8},     {"int8", VoxelType::I8},
        {"int8_t", VoxelType::I8},          {"uchar", VoxelType::U8},
        {"unsigned char", VoxelType::U8},   {"uint8", VoxelType::U8},
        {"uint8_t", VoxelType::U8},         {"short", VoxelType::I16},
        {"short int", VoxelType::I16},      {"signed short", VoxelType::I16},
        {"signed short int", VoxelType::I16}, {"int16", VoxelType::I16},
        {"int16_t", VoxelType::I16},        {"ushort", VoxelType::U16},
        {"unsigned short", VoxelType::U16}, {"unsigned short int", VoxelType::U16},
        {"uint16", VoxelType::U16},         {"uint16_t", VoxelType::U16},
        {"int", VoxelType::I32},            {"signed int", VoxelType::I32},
        {"int32", VoxelType::I32},          {"int32_t", VoxelType::I32},
        {"uint", VoxelType::U32},           {"unsigned int", VoxelType::U32},
        {"uint32", VoxelType::U32},         {"uint32_t", VoxelType::U32},
        {"float", VoxelType::F32},          {"double", VoxelType::F64},
    };
    for (const Spelling& s : kSpellings) {
        if (name == s.name) return s.type;
    }
    static constexpr const char* kKnownUnsupported[] = {
        "longlong",  "long long", "long long int", "signed long long", "signed long long int",
        "int64",     "int64_t",   "ulonglong",     "unsigned long long", "unsigned long long int",
        "uint64",    "uint64_t",  "block"};
    for (const char* s : kKnownUnsupported) {
        if (name == s) {
            throw InputError(ctx + ": unsupported type '" + name +
                             "' (cutaway reads 8, 16 and 32-bit integers, float and double)");
        }
    }
    throw InputError(ctx + ": unknown type '" + std::string(text) + "'");
}

std::int64_t parseIntField(const std::string& text, const char* field, const std::string& ctx) {
    std::int64_t value = 0;
    if (!detail::parseInt(trim(text), value)) {
        throw InputError(ctx + ": field '" + field + "' is not an integer: '" + text + "'");
    }
    return value;
}

/// Parses "(a,b,c)" vectors and "none" entries of `space directions` / `space origin`.
std::vector<std::optional<std::vector<double>>> parseVectors(std::string_view text,
                                                             const char* field,
                                                             const std::string& ctx) {
    std::vector<std::optional<std::vector<double>>> out;
    const auto bad = [&]() {
        return InputError(ctx + ": malformed '" + field + "': '" + std::string(trim(text)) +
                          "' (expected vectors like (1,0,0) or none)");
    };
    std::string_view rest = trim(text);
    while (!rest.empty()) {
        if (rest.size() >= 4 && toLower(rest.substr(0, 4)) == "none") {
            out.emplace_back(std::nullopt);
            rest = trim(rest.substr(4));
            continue;
        }
        if (rest.front() != '(') throw bad();
        const std::size_t close = rest.find(')');
        if (close == std::string_view::npos) throw bad();
        std::vector<double> vec;
        std::string_view inner = rest.substr(1, close - 1);
        while (true) {
            const std::size_t comma = inner.find(',');
            double value = 0.0;
            if (!detail::parseDouble(trim(inner.substr(0, comma)), value)) throw bad();
            vec.push_back(value);
            if (comma == std::string_view::npos) break;
            inner.remove_prefix(comma + 1);
        }
        out.emplace_back(std::move(vec));
        rest = trim(rest.substr(close + 1));
    }
    return out;
}

NrrdFields readHeader(std::istream& in, const std::string& ctx, bool& endedByBlankLine) {
    std::size_t budget = kMaxHeaderBytes;
    std::string line;
    if (!readLine(in, line, budget, ctx)) throw InputError(ctx + ": empty file, not a NRRD file");
    const std::string_view magic = trim(line);
    if (magic.size() != 8 || magic.substr(0, 7) != "NRRD000" || magic[7] < '1' || magic[7] > '5') {
        throw InputError(ctx + ": not a NRRD file (expected the magic NRRD0001..NRRD0005, found '" +
                         std::string(magic.substr(0, 16)) + "')");
    }
    NrrdFields f;
    endedByBlankLine = false;
    int lineNumber = 1;
    while (readLine(in, line, budget, ctx)) {
        ++lineNumber;
        if (trim(line).empty()) {
            endedByBlankLine = true;
            break;
        }
        if (line.front() == '#') continue;
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos) {
            throw InputError(ctx + ": line " + std::to_string(lineNumber) + ": expected 'field: value', found '" +
                             line.substr(0, 80) + "'");
        }
        if (colon + 1 < line.size() && line[colon + 1] == '=') {
            // key:=value pairs are free-form; cutaway's writer keeps a NIfTI-style
            // value scaling in two of them so it survives a round trip.
            const std::string key(trim(std::string_view(line).substr(0, colon)));
            const std::string value(trim(std::string_view(line).substr(colon + 2)));
            if (key == "cutaway_slope") f.slope = value;
            if (key == "cutaway_inter") f.inter = value;
            continue;
        }
        const std::string name = toLower(trim(std::string_view(line).substr(0, colon)));
        std::string value(trim(std::string_view(line).substr(colon + 1)));
        if (name == "type") f.type = value;
        else if (name == "dimension") f.dimension = value;
        else if (name == "sizes") f.sizes = value;
        else if (name == "endian") f.endian = value;
        else if (name == "encoding") f.encoding = value;
        else if (name == "spacings") f.spacings = value;
        else if (name == "space directions") f.directions = value;
        else if (name == "space origin") f.origin = value;
        else if (name == "data file" || name == "datafile") f.dataFile = value;
        else if (name == "byte skip" || name == "byteskip") f.byteSkip = value;
        else if (name == "line skip" || name == "lineskip") f.lineSkip = value;
        // content, kinds, space, centerings, labels, units, ...: descriptive only.
    }
    return f;
}

const std::string& required(const std::optional<std::string>& field, const char* name,
                            const std::string& ctx) {
    if (!field) throw InputError(ctx + ": missing required field '" + name + "'");
    return *field;
}

} // namespace

Volume readNrrd(const std::filesystem::path& path) {
    const std::string ctx = path.string();
    const std::uint64_t headerFileSize = detail::regularFileSize(path);
    std::ifstream in = detail::openBinary(path);
    bool endedByBlankLine = false;
    const NrrdFields f = readHeader(in, ctx, endedByBlankLine);

    const VoxelType type = parseNrrdType(required(f.type, "type", ctx), ctx);
    const std::int64_t dimension = parseIntField(required(f.dimension, "dimension", ctx), "dimension", ctx);
    if (dimension != 3 && dimension != 4) {
        throw InputError(ctx + ": dimension " + std::to_string(dimension) +
                         " is not supported (cutaway reads 3D volumes: dimension 3, or 4 with a "
                         "first axis of size 1)");
    }
    const auto first = static_cast<std::size_t>(dimension - 3); // index of the x axis

    const auto sizeWords = splitWords(required(f.sizes, "sizes", ctx));
    if (static_cast<std::int64_t>(sizeWords.size()) != dimension) {
        throw InputError(ctx + ": 'sizes' has " + std::to_string(sizeWords.size()) +
                         " entries but dimension is " + std::to_string(dimension));
    }
    std::int64_t all[4] = {};
    for (std::size_t a = 0; a < sizeWords.size(); ++a) {
        if (!detail::parseInt(sizeWords[a], all[a])) {
            throw InputError(ctx + ": 'sizes' entry '" + std::string(sizeWords[a]) +
                             "' is not an integer");
        }
    }
    if (dimension == 4 && all[0] != 1) {
        throw InputError(ctx + ": dimension 4 is only supported with a first axis of size 1 (got " +
                         std::to_string(all[0]) + ")");
    }
    const std::int64_t sizes[3] = {all[first], all[first + 1], all[first + 2]};
    const std::size_t bytes = detail::checkedByteCount(sizes, type, ctx);

    Volume volume;
    volume.dims = glm::ivec3(static_cast<int>(sizes[0]), static_cast<int>(sizes[1]),
                             static_cast<int>(sizes[2]));
    volume.type = type;
    // Spacing: the length of each space direction, else `spacings`, else 1 mm.
    if (f.directions) {
        const auto vectors = parseVectors(*f.directions, "space directions", ctx);
        if (static_cast<std::int64_t>(vectors.size()) != dimension) {
            throw InputError(ctx + ": 'space directions' has " + std::to_string(vectors.size()) +
                             " entries but dimension is " + std::to_string(dimension));
        }
        for (int a = 0; a < 3; ++a) {
            const auto& v = vectors[first + static_cast<std::size_t>(a)];
            if (!v) throw InputError(ctx + ": 'space directions' is none for a spatial axis");
            double squared = 0.0;
            for (double c : *v) squared += c * c;
            volume.spacing[a] = std::sqrt(squared);
            detail::checkSpacing(volume.spacing[a], a, ctx);
        }
    } else if (f.spacings) {
        const auto words = splitWords(*f.spacings);
        if (static_cast<std::int64_t>(words.size()) != dimension) {
            throw InputError(ctx + ": 'spacings' has " + std::to_string(words.size()) +
                             " entries but dimension is " + std::to_string(dimension));
        }
        for (int a = 0; a < 3; ++a) {
            const auto word = words[first + static_cast<std::size_t>(a)];
            if (!detail::parseDouble(word, volume.spacing[a])) {
                throw InputError(ctx + ": 'spacings' entry '" + std::string(word) +
                                 "' is not a number");
            }
            detail::checkSpacing(volume.spacing[a], a, ctx);
        }
    }
    if (f.origin) {
        const auto vectors = parseVectors(*f.origin, "space origin", ctx);
        if (vectors.size() != 1 || !vectors[0]) {
            throw InputError(ctx + ": 'space origin' must be one vector like (0,0,0)");
        }
        for (std::size_t a = 0; a < std::min<std::size_t>(3, vectors[0]->size()); ++a) {
            volume.origin[static_cast<int>(a)] = (*vectors[0])[a];
        }
    }

    if (f.slope || f.inter) {
        double slope = 1.0;
        double inter = 0.0;
        if ((f.slope && !detail::parseDouble(*f.slope, slope)) ||
            (f.inter && !detail::parseDouble(*f.inter, inter)) || !std::isfinite(slope) ||
            slope == 0.0 || !std::isfinite(inter)) {
            throw InputError(ctx + ": invalid cutaway_slope / cutaway_inter value scaling");
        }
        volume.slope = slope;
        volume.inter = inter;
    }

    bool bigEndian = false; // a missing endian (legal for 8-bit data) means little
    if (f.endian) {
        const std::string endian = toLower(trim(*f.endian));
        if (endian == "big") bigEndian = true;
        else if (endian != "little") throw InputError(ctx + ": unknown endian '" + *f.endian + "'");
    }
    const std::string encoding = toLower(trim(required(f.encoding, "encoding", ctx)));
    const bool gzip = encoding == "gzip" || encoding == "gz";
    if (!gzip && encoding != "raw") {
        throw InputError(ctx + ": unsupported encoding '" + encoding + "' (supported: raw, gzip)");
    }
    const std::int64_t byteSkip = f.byteSkip ? parseIntField(*f.byteSkip, "byte skip", ctx) : 0;
    const std::int64_t lineSkip = f.lineSkip ? parseIntField(*f.lineSkip, "line skip", ctx) : 0;
    if (byteSkip < -1 || byteSkip > static_cast<std::int64_t>(detail::kMaxBytes)) {
        throw InputError(ctx + ": invalid byte skip " + std::to_string(byteSkip));
    }
    if (byteSkip == -1 && gzip) {
        throw InputError(ctx + ": byte skip -1 is only valid with raw encoding");
    }
    if (lineSkip < 0) throw InputError(ctx + ": invalid line skip " + std::to_string(lineSkip));

    // The data: after the header's blank line, or in a detached data file.
    std::filesystem::path dataPath = path;
    std::ifstream detached;
    std::istream* data = &in;
    std::string dataCtx = ctx;
    std::uint64_t dataFileSize = headerFileSize;
    if (f.dataFile) {
        const std::string name(trim(*f.dataFile));
        if (name.rfind("LIST", 0) == 0 || (name.find('%') != std::string::npos &&
                                           name.find(' ') != std::string::npos)) {
            throw InputError(ctx + ": multi-file 'data file' lists are not supported ('" + name +
                             "'); use a single data file");
        }
        dataPath = std::filesystem::path(name);
        if (dataPath.is_relative()) dataPath = path.parent_path() / dataPath;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(dataPath, ec)) {
            throw InputError(ctx + ": data file '" + name + "' not found (looked at " +
                             dataPath.string() + ")");
        }
        dataFileSize = detail::regularFileSize(dataPath);
        detached = detail::openBinary(dataPath);
        data = &detached;
        dataCtx = ctx + " (data file " + dataPath.string() + ")";
    } else if (!endedByBlankLine) {
        throw InputError(ctx + ": no data: the header has no blank line after it and no 'data "
                               "file' field");
    }
    std::size_t unused = std::numeric_limits<std::size_t>::max();
    std::string skipped;
    for (std::int64_t i = 0; i < lineSkip; ++i) {
        if (!readLine(*data, skipped, unused, dataCtx)) {
            throw InputError(dataCtx + ": line skip " + std::to_string(lineSkip) +
                             " goes past the end of the file");
        }
    }

    if (!gzip) {
        auto start = static_cast<std::uint64_t>(data->tellg());
        if (byteSkip == -1) {
            // Data at the end of the file, whatever comes before it.
            if (dataFileSize < bytes) start = dataFileSize + 1;
            else start = dataFileSize - bytes;
        } else {
            start += static_cast<std::uint64_t>(byteSkip);
        }
        const std::uint64_t available = start <= dataFileSize ? dataFileSize - start : 0;
        if (start > dataFileSize || available < bytes) {
            throw InputError(dataCtx + ": data truncated: expected " + std::to_string(bytes) +
                             " bytes after the header, found " + std::to_string(available));
        }
        data->seekg(static_cast<std::streamoff>(start));
        volume.data.resize(bytes);
        if (detail::readSome(*data, volume.data.data(), bytes) != bytes) {
            throw InputError(dataCtx + ": read error in the voxel data");
        }
    } else {
        detail::GzipReader reader(*data, dataCtx);
        // For compressed data the byte skip counts decompressed bytes.
        if (reader.skip(static_cast<std::uint64_t>(byteSkip)) < static_cast<std::uint64_t>(byteSkip)) {
            throw InputError(dataCtx + ": data truncated: byte skip " + std::to_string(byteSkip) +
                             " goes past the end of the decompressed data");
        }
        volume.data = detail::readUpTo(reader, bytes);
        if (volume.data.size() < bytes) {
            throw InputError(dataCtx + ": data truncated: expected " + std::to_string(bytes) +
                             " bytes after decompression, found " +
                             std::to_string(volume.data.size()));
        }
        std::byte extra{};
        if (reader.read(&extra, 1) != 0) {
            throw InputError(dataCtx + ": decompressed data exceeds the declared size (" +
                             std::to_string(bytes) + " bytes)");
        }
    }
    if (detail::needsSwap(bigEndian)) {
        detail::swapBytes(volume.data.data(), volume.voxelCount(), voxelSize(type));
    }
    return volume;
}

} // namespace cutaway
