// MetaImage (ITK's .mha, and .mhd with a separate data file): "Key = Value"
// lines ending with ElementDataFile, then the voxels (LOCAL) or the named
// file. Read: 2 or 3 dimensions, one channel, the MET_ element types of
// volume.hpp's voxel types, either byte order, raw or zlib-compressed data,
// HeaderSize (-1: the data file's last bytes), Offset and TransformMatrix
// (with their synonyms Origin, Position, Rotation, Orientation), in ITK's
// LPS space. Refused, with a message: ASCII data, several channels, more
// dimensions, and data split over several files (LIST, patterns).
#include "core/error.hpp"
#include "core/quote_text.hpp"
#include "io/input_file.hpp"
#include "volume/byte_order.hpp"
#include "volume/io_util.hpp"
#include "volume/volume.hpp"
#include "volume/voxel_data.hpp"

#include <cmath>
#include <map>
#include <optional>
#include <sstream>

namespace cutaway {
namespace {

using detail::toLower;
using detail::trim;

// Longest header accepted: ITK's run to a few hundred bytes.
constexpr std::size_t kMaxHeader = 1 << 16;

struct MetaHeader {
    std::map<std::string, std::string> fields; // keys in lower case
    std::string ctx;

    std::optional<std::string> get(const char* key) const {
        const auto it = fields.find(key);
        if (it == fields.end()) return std::nullopt;
        return it->second;
    }
    std::optional<std::string> any(std::initializer_list<const char*> keys) const {
        for (const char* k : keys)
            if (auto v = get(k)) return v;
        return std::nullopt;
    }
};

// Reads one line (without its newline) into `line`, taking its bytes from
// `budget` as they are read: a line that never ends stops at the budget, not
// at the end of a 20 GB file. False at the end of the input.
bool boundedLine(std::istream& in, std::string& line, std::size_t& budget, const std::string& ctx) {
    line.clear();
    std::streambuf* buffer = in.rdbuf();
    bool any = false;
    for (int c; (c = buffer->sbumpc()) != std::char_traits<char>::eof();) {
        any = true;
        if (budget-- == 0)
            throw InputError(ctx + ": no ElementDataFile within the first 64 KiB of the header");
        if (c == '\n') break;
        line.push_back(static_cast<char>(c));
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return any;
}

// The header's lines up to and including ElementDataFile.
MetaHeader readHeader(std::istream& in, const std::string& ctx) {
    MetaHeader h;
    h.ctx = ctx;
    std::string line;
    std::size_t budget = kMaxHeader;
    while (boundedLine(in, line, budget, ctx)) {
        if (trim(line).empty()) continue;
        const std::size_t eq = line.find('=');
        if (eq == std::string::npos)
            throw InputError(ctx +
                             ": not a MetaImage header line (no '='): " + quoteText(trim(line)));
        const std::string key = toLower(trim(line.substr(0, eq)));
        h.fields[key] = std::string(trim(line.substr(eq + 1)));
        if (key == "elementdatafile") return h;
    }
    throw InputError(ctx + ": the header ends without ElementDataFile");
}

std::vector<double> numbers(const MetaHeader& h, const char* key, const std::string& text,
                            std::size_t count) {
    std::istringstream words(text);
    std::vector<double> out;
    std::string word;
    while (words >> word) {
        double v = 0.0;
        if (!detail::parseDouble(word, v) || !std::isfinite(v))
            throw InputError(h.ctx + ": " + key + ": " + quoteText(word) +
                             " is not a finite number");
        out.push_back(v);
    }
    if (out.size() != count)
        throw InputError(h.ctx + ": " + key + ": expected " + std::to_string(count) +
                         " numbers, got " + std::to_string(out.size()));
    return out;
}

bool flag(const MetaHeader& h, const char* key, bool otherwise) {
    const std::optional<std::string> v = h.get(key);
    if (!v) return otherwise;
    const std::string t = toLower(*v);
    if (t == "true" || t == "1") return true;
    if (t == "false" || t == "0") return false;
    throw InputError(h.ctx + ": " + key + ": expected True or False, got " + quoteText(*v));
}

VoxelType elementType(const MetaHeader& h) {
    const std::optional<std::string> t = h.get("elementtype");
    if (!t) throw InputError(h.ctx + ": missing ElementType");
    static const std::map<std::string, VoxelType> kTypes = {
        {"MET_UCHAR", VoxelType::U8},   {"MET_CHAR", VoxelType::I8},
        {"MET_USHORT", VoxelType::U16}, {"MET_SHORT", VoxelType::I16},
        {"MET_UINT", VoxelType::U32},   {"MET_INT", VoxelType::I32},
        {"MET_FLOAT", VoxelType::F32},  {"MET_DOUBLE", VoxelType::F64}};
    const auto it = kTypes.find(*t);
    if (it == kTypes.end())
        throw InputError(h.ctx + ": ElementType " + quoteText(*t) +
                         " is not read (MET_UCHAR, MET_CHAR, MET_USHORT, MET_SHORT, MET_UINT, "
                         "MET_INT, MET_FLOAT, MET_DOUBLE)");
    return it->second;
}

// Dimensions, type, spacing and placement; the data's layout is the caller's.
// The directions must span space: no axis of length zero or not finite,
// none (nearly) along another. Each is made unit length, as ITK reads them.
void checkDirections(glm::dmat3& direction, const std::string& ctx) {
    for (int c = 0; c < 3; ++c) {
        const double length = glm::length(direction[c]);
        if (!std::isfinite(length) || length < 1e-6)
            throw InputError(ctx + ": TransformMatrix: axis " + std::to_string(c) +
                             "'s direction has length " + detail::formatDouble(length) +
                             " (each axis needs a direction)");
        direction[c] /= length;
    }
    const double det = glm::determinant(direction);
    if (std::abs(det) < 1e-3)
        throw InputError(ctx + ": TransformMatrix is singular (determinant " +
                         detail::formatDouble(det) +
                         " once its axes are unit length): two axes point the same way");
}

Volume readGrid(const MetaHeader& h) {
    if (const auto object = h.get("objecttype"); object && toLower(*object) != "image")
        throw InputError(h.ctx + ": ObjectType '" + *object + "' is not an image");
    std::int64_t ndims = 0;
    if (!h.get("ndims") || !detail::parseInt(*h.get("ndims"), ndims) || ndims < 2 || ndims > 3)
        throw InputError(h.ctx + ": NDims must be 2 or 3, got '" + h.get("ndims").value_or("") +
                         "'");
    const std::size_t n = std::size_t(ndims);
    if (const auto channels = h.get("elementnumberofchannels"); channels && trim(*channels) != "1")
        throw InputError(h.ctx + ": " + *channels + " channels per voxel; only scalar images");
    if (!flag(h, "binarydata", true))
        throw InputError(h.ctx + ": BinaryData = False (ASCII voxels) is not read");
    const auto dimText = h.get("dimsize");
    if (!dimText) throw InputError(h.ctx + ": missing DimSize");
    const std::vector<double> dims = numbers(h, "DimSize", *dimText, n);
    std::int64_t sizes[3] = {1, 1, 1};
    for (std::size_t a = 0; a < n; ++a) {
        if (dims[a] != std::floor(dims[a]) || dims[a] < 1 || dims[a] > 1e9)
            throw InputError(h.ctx + ": DimSize: " + detail::formatDouble(dims[a]) +
                             " is not a size");
        sizes[a] = std::int64_t(dims[a]);
    }
    Volume v;
    v.type = elementType(h);
    detail::checkedByteCount(sizes, v.type, h.ctx);
    v.dims = glm::ivec3(int(sizes[0]), int(sizes[1]), int(sizes[2]));
    if (const auto s = h.get("elementspacing")) {
        const std::vector<double> spacing = numbers(h, "ElementSpacing", *s, n);
        for (std::size_t a = 0; a < n; ++a) {
            detail::checkSpacing(spacing[a], int(a), h.ctx);
            v.spacing[int(a)] = spacing[a];
        }
    }
    const auto offset = h.any({"offset", "origin", "position"});
    const auto matrix = h.any({"transformmatrix", "rotation", "orientation"});
    if (offset) {
        const std::vector<double> o = numbers(h, "Offset", *offset, n);
        for (std::size_t a = 0; a < n; ++a)
            v.origin[int(a)] = o[a];
    }
    if (matrix) {
        const std::vector<double> m = numbers(h, "TransformMatrix", *matrix, n * n);
        for (std::size_t c = 0; c < n; ++c) // axis c's direction: the c-th n numbers
            for (std::size_t r = 0; r < n; ++r)
                v.direction[int(c)][int(r)] = m[c * n + r];
        checkDirections(v.direction, h.ctx);
    }
    if (offset || matrix || h.get("anatomicalorientation")) v.space = Space::LPS;
    return v;
}

Volume readMetaImageStream(std::istream& in, std::uint64_t fileSize, const std::string& ctx,
                           const std::optional<std::filesystem::path>& folder) {
    const MetaHeader h = readHeader(in, ctx);
    Volume v = readGrid(h);
    const bool compressed = flag(h, "compresseddata", false);
    const bool bigEndian = flag(h, "binarydatabyteordermsb", flag(h, "elementbyteordermsb", false));
    std::int64_t skip = 0;
    if (const auto s = h.get("headersize"); s && (!detail::parseInt(*s, skip) || skip < -1))
        throw InputError(ctx + ": HeaderSize: expected a byte count or -1, got " + quoteText(*s));
    if (skip == -1 && compressed)
        throw InputError(ctx + ": HeaderSize -1 is only valid with uncompressed data");
    const std::string name = *h.get("elementdatafile");
    const std::size_t bytes = v.voxelCount() * voxelSize(v.type);
    std::optional<InputFile> detached;
    detail::VoxelSource source{&in, ctx, fileSize};
    if (toLower(name) != "local") {
        if (toLower(name).rfind("list", 0) == 0 || name.find('%') != std::string::npos)
            throw InputError(ctx + ": ElementDataFile '" + name +
                             "': data over several files is not read; write one data file");
        if (!folder)
            throw InputError(ctx + ": ElementDataFile '" + name +
                             "' cannot be read: a header read from memory has no folder");
        std::filesystem::path data(name);
        if (data.is_relative()) data = *folder / data;
        detached.emplace(data, "it",
                         ctx + ": ElementDataFile '" + name + "' (" + data.string() + ")");
        source = {&detached->stream(), ctx + " (data file " + data.string() + ")",
                  detached->size()};
    }
    v.data = compressed ? detail::readCompressedVoxels(source, skip, bytes)
                        : detail::readRawVoxels(source, skip, bytes);
    if (detail::needsSwap(bigEndian))
        detail::swapBytes(v.data.data(), v.voxelCount(), voxelSize(v.type));
    return v;
}

} // namespace

Volume readMetaImage(const std::filesystem::path& path) {
    InputFile file(path, "volume");
    return readMetaImageStream(file.stream(), file.size(), path.string(), path.parent_path());
}

Volume readMetaImageBytes(std::span<const std::byte> bytes, const std::string& name) {
    detail::MemoryBuffer buffer(bytes);
    std::istream in(&buffer);
    return readMetaImageStream(in, bytes.size(), name, std::nullopt);
}

std::optional<std::filesystem::path> metaImageDataFile(const std::filesystem::path& path) {
    try {
        InputFile file(path, "volume");
        const std::string name = *readHeader(file.stream(), path.string()).get("elementdatafile");
        if (toLower(name) == "local") return std::nullopt;
        const std::filesystem::path data(name);
        return data.is_relative() ? path.parent_path() / data : data;
    } catch (const InputError&) {
        return std::nullopt; // reading the volume says what is wrong with it
    }
}

} // namespace cutaway
