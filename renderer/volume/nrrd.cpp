// NRRD reader (http://teem.sourceforge.net/nrrd/format.html), NRRD0001..NRRD0005:
// attached (.nrrd) and detached (.nhdr + data file) headers, raw and gzip
// encodings, either byte order, 3D grids (or 4D with a first axis of size 1).
// Geometry from `space` (or `space dimension`), `space directions` and `space
// origin`, anatomical spaces converted to LPS (volume.hpp); else `spacings`.
#include "core/error.hpp"
#include "core/quote_text.hpp"
#include "io/input_file.hpp"
#include "volume/byte_order.hpp"
#include "volume/gzip.hpp"
#include "volume/io_util.hpp"
#include "volume/nrrd_header.hpp"
#include "volume/volume.hpp"
#include "volume/voxel_data.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace cutaway {

namespace {

using detail::parseNrrdType;
using detail::parseNrrdVectors;
using detail::readNrrdHeader;
using detail::readNrrdLine;
using detail::splitWords;
using detail::toLower;
using detail::trim;

std::int64_t parseIntField(const std::string& text, const char* field, const std::string& ctx) {
    std::int64_t value = 0;
    if (!detail::parseInt(trim(text), value)) {
        throw InputError(ctx + ": field '" + field + "' is not an integer: " + quoteText(text));
    }
    return value;
}

const std::string& required(const std::optional<std::string>& field, const char* name,
                            const std::string& ctx) {
    if (!field) throw InputError(ctx + ": missing required field '" + name + "'");
    return *field;
}

/// What the `space` / `space dimension` fields say: the space cutaway keeps
/// the geometry in, how many components the file's vectors have, and the
/// factors that take its first three components to LPS.
struct NrrdSpace {
    Space space = Space::NonAnatomical;
    std::size_t dimension = 0; ///< 0: not stated (taken from the vectors, which must have 3)
    glm::dvec3 toLps{1.0};
};

NrrdSpace parseSpace(const detail::NrrdFields& f, const std::string& ctx) {
    struct Named {
        const char* name;
        Space space;
        std::size_t dimension;
        glm::dvec3 toLps;
    };
    // The spec's spaces and the spellings teem accepts for them (any case).
    static const Named kSpaces[] = {
        {"right-anterior-superior", Space::LPS, 3, {-1, -1, 1}},
        {"right anterior superior", Space::LPS, 3, {-1, -1, 1}},
        {"rightanteriorsuperior", Space::LPS, 3, {-1, -1, 1}},
        {"ras", Space::LPS, 3, {-1, -1, 1}},
        {"left-anterior-superior", Space::LPS, 3, {1, -1, 1}},
        {"left anterior superior", Space::LPS, 3, {1, -1, 1}},
        {"leftanteriorsuperior", Space::LPS, 3, {1, -1, 1}},
        {"las", Space::LPS, 3, {1, -1, 1}},
        {"left-posterior-superior", Space::LPS, 3, {1, 1, 1}},
        {"left posterior superior", Space::LPS, 3, {1, 1, 1}},
        {"leftposteriorsuperior", Space::LPS, 3, {1, 1, 1}},
        {"lps", Space::LPS, 3, {1, 1, 1}},
        {"right-anterior-superior-time", Space::LPS, 4, {-1, -1, 1}},
        {"right anterior superior time", Space::LPS, 4, {-1, -1, 1}},
        {"rightanteriorsuperiortime", Space::LPS, 4, {-1, -1, 1}},
        {"rast", Space::LPS, 4, {-1, -1, 1}},
        {"left-anterior-superior-time", Space::LPS, 4, {1, -1, 1}},
        {"left anterior superior time", Space::LPS, 4, {1, -1, 1}},
        {"leftanteriorsuperiortime", Space::LPS, 4, {1, -1, 1}},
        {"last", Space::LPS, 4, {1, -1, 1}},
        {"left-posterior-superior-time", Space::LPS, 4, {1, 1, 1}},
        {"left posterior superior time", Space::LPS, 4, {1, 1, 1}},
        {"leftposteriorsuperiortime", Space::LPS, 4, {1, 1, 1}},
        {"lpst", Space::LPS, 4, {1, 1, 1}},
        {"scanner-xyz", Space::NonAnatomical, 3, {1, 1, 1}},
        {"scanner-xyz-time", Space::NonAnatomical, 4, {1, 1, 1}},
        {"scanner-xyzt", Space::NonAnatomical, 4, {1, 1, 1}},
        {"3d-right-handed", Space::NonAnatomical, 3, {1, 1, 1}},
        {"3d right handed", Space::NonAnatomical, 3, {1, 1, 1}},
        {"3drighthanded", Space::NonAnatomical, 3, {1, 1, 1}},
        {"3d-left-handed", Space::NonAnatomical, 3, {1, 1, 1}},
        {"3d left handed", Space::NonAnatomical, 3, {1, 1, 1}},
        {"3dlefthanded", Space::NonAnatomical, 3, {1, 1, 1}},
        {"3d-right-handed-time", Space::NonAnatomical, 4, {1, 1, 1}},
        {"3d right handed time", Space::NonAnatomical, 4, {1, 1, 1}},
        {"3drighthandedtime", Space::NonAnatomical, 4, {1, 1, 1}},
        {"3d-left-handed-time", Space::NonAnatomical, 4, {1, 1, 1}},
        {"3d left handed time", Space::NonAnatomical, 4, {1, 1, 1}},
        {"3dlefthandedtime", Space::NonAnatomical, 4, {1, 1, 1}},
    };
    NrrdSpace out;
    if (f.space) {
        const std::string name = toLower(trim(*f.space));
        const Named* found = nullptr;
        for (const Named& n : kSpaces)
            if (name == n.name) found = &n;
        if (!found) {
            throw InputError(ctx + ": unknown space '" + std::string(trim(*f.space)) +
                             "' (expected one of the NRRD spaces, e.g. left-posterior-superior, "
                             "right-anterior-superior, scanner-xyz, 3D-right-handed)");
        }
        out = {found->space, found->dimension, found->toLps};
    }
    if (f.spaceDimension) {
        const std::int64_t n = parseIntField(*f.spaceDimension, "space dimension", ctx);
        if (f.space && n != static_cast<std::int64_t>(out.dimension)) {
            throw InputError(ctx + ": 'space dimension' " + std::to_string(n) +
                             " contradicts space " + quoteText(trim(*f.space)));
        }
        if (n != 3 && !f.space) {
            throw InputError(ctx + ": space dimension " + std::to_string(n) +
                             " is not supported (cutaway reads volumes in a 3D space)");
        }
        out.dimension = static_cast<std::size_t>(n);
    }
    return out;
}

// The one vector of a `space origin` field.
std::vector<double> originVector(std::string_view text, const std::string& ctx) {
    auto origins = parseNrrdVectors(text, "space origin", ctx);
    if (origins.size() != 1 || !origins[0]) {
        throw InputError(ctx + ": 'space origin' must be one vector like (0,0,0)");
    }
    return std::move(*origins[0]);
}

/// The first three components of a `space directions` or `space origin`
/// vector, in LPS for an anatomical space. Its length must be the space's
/// dimension (3 when the header states none).
glm::dvec3 spatialPart(const std::vector<double>& v, const NrrdSpace& space, const char* field,
                       const std::string& ctx) {
    const std::size_t want = space.dimension ? space.dimension : 3;
    if (v.size() != want) {
        throw InputError(ctx + ": a '" + field + "' vector has " + std::to_string(v.size()) +
                         " components but the space has " + std::to_string(want) + " dimensions");
    }
    return glm::dvec3(v[0], v[1], v[2]) * space.toLps;
}

/// The grid a header declares: its voxel type, dimension (3, or 4 with a
/// first axis of size 1), the index of its x axis, sizes and data bytes.
struct NrrdGrid {
    VoxelType type{};
    std::int64_t dimension = 3;
    std::size_t first = 0; ///< index of the x axis
    std::int64_t sizes[3] = {};
    std::size_t bytes = 0;
};

NrrdGrid readGrid(const detail::NrrdFields& f, const std::string& ctx) {
    NrrdGrid g;
    g.type = parseNrrdType(required(f.type, "type", ctx), ctx);
    g.dimension = parseIntField(required(f.dimension, "dimension", ctx), "dimension", ctx);
    if (g.dimension != 3 && g.dimension != 4) {
        throw InputError(ctx + ": dimension " + std::to_string(g.dimension) +
                         " is not supported (cutaway reads 3D volumes: dimension 3, or 4 with a "
                         "first axis of size 1)");
    }
    g.first = static_cast<std::size_t>(g.dimension - 3);
    const auto sizeWords = splitWords(required(f.sizes, "sizes", ctx));
    if (static_cast<std::int64_t>(sizeWords.size()) != g.dimension) {
        throw InputError(ctx + ": 'sizes' has " + std::to_string(sizeWords.size()) +
                         " entries but dimension is " + std::to_string(g.dimension));
    }
    std::int64_t all[4] = {};
    for (std::size_t a = 0; a < sizeWords.size(); ++a) {
        if (!detail::parseInt(sizeWords[a], all[a])) {
            throw InputError(ctx + ": 'sizes' entry '" + std::string(sizeWords[a]) +
                             "' is not an integer");
        }
    }
    if (g.dimension == 4 && all[0] != 1) {
        throw InputError(ctx + ": dimension 4 is only supported with a first axis of size 1 (got " +
                         std::to_string(all[0]) + ")");
    }
    for (int a = 0; a < 3; ++a)
        g.sizes[a] = all[g.first + static_cast<std::size_t>(a)];
    g.bytes = detail::checkedByteCount(g.sizes, g.type, ctx);
    return g;
}

/// Spacing, directions and origin from the space directions.
void readSpaceGeometry(const detail::NrrdFields& f, const NrrdGrid& g, Volume& volume,
                       const std::string& ctx) {
    const NrrdSpace space = parseSpace(f, ctx);
    const auto vectors = parseNrrdVectors(*f.directions, "space directions", ctx);
    if (static_cast<std::int64_t>(vectors.size()) != g.dimension) {
        throw InputError(ctx + ": 'space directions' has " + std::to_string(vectors.size()) +
                         " entries but dimension is " + std::to_string(g.dimension));
    }
    for (int a = 0; a < 3; ++a) {
        const auto& v = vectors[g.first + static_cast<std::size_t>(a)];
        if (!v) throw InputError(ctx + ": 'space directions' is none for a spatial axis");
        const glm::dvec3 vector = spatialPart(*v, space, "space directions", ctx);
        volume.spacing[a] = glm::length(vector);
        detail::checkSpacing(volume.spacing[a], a, ctx);
        volume.direction[a] = vector / volume.spacing[a];
    }
    volume.space = space.space;
    if (f.origin) {
        volume.origin = spatialPart(originVector(*f.origin, ctx), space, "space origin", ctx);
        if (!std::isfinite(volume.origin.x) || !std::isfinite(volume.origin.y) ||
            !std::isfinite(volume.origin.z)) {
            throw InputError(ctx + ": 'space origin' is not finite");
        }
    }
}

/// Spacing (the length of each space direction, else `spacings`, else 1 mm),
/// directions and origin.
void readGeometry(const detail::NrrdFields& f, const NrrdGrid& g, Volume& volume,
                  const std::string& ctx) {
    if (f.directions) {
        readSpaceGeometry(f, g, volume, ctx);
        return;
    }
    if (f.spacings) {
        const auto words = splitWords(*f.spacings);
        if (static_cast<std::int64_t>(words.size()) != g.dimension) {
            throw InputError(ctx + ": 'spacings' has " + std::to_string(words.size()) +
                             " entries but dimension is " + std::to_string(g.dimension));
        }
        for (int a = 0; a < 3; ++a) {
            const auto word = words[g.first + static_cast<std::size_t>(a)];
            if (!detail::parseDouble(word, volume.spacing[a])) {
                throw InputError(ctx + ": 'spacings' entry '" + std::string(word) +
                                 "' is not a number");
            }
            detail::checkSpacing(volume.spacing[a], a, ctx);
        }
    }
    // Without space directions the axes have no orientation in a space: an
    // origin is kept as written, for reference.
    if (f.origin) {
        const std::vector<double> origin = originVector(*f.origin, ctx);
        for (std::size_t a = 0; a < std::min<std::size_t>(3, origin.size()); ++a) {
            volume.origin[static_cast<int>(a)] = origin[a];
        }
    }
}

/// cutaway's own value scaling fields (cutaway_slope, cutaway_inter).
void readScaling(const detail::NrrdFields& f, Volume& volume, const std::string& ctx) {
    if (!f.slope && !f.inter) return;
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

/// How the data is stored: byte order, encoding and what comes before it.
struct NrrdEncoding {
    bool bigEndian = false;
    bool gzip = false;
    std::int64_t byteSkip = 0;
    std::int64_t lineSkip = 0;
};

NrrdEncoding readEncoding(const detail::NrrdFields& f, const std::string& ctx) {
    NrrdEncoding e; // a missing endian (legal for 8-bit data) means little
    if (f.endian) {
        const std::string endian = toLower(trim(*f.endian));
        if (endian == "big")
            e.bigEndian = true;
        else if (endian != "little")
            throw InputError(ctx + ": unknown endian " + quoteText(*f.endian));
    }
    const std::string encoding = toLower(trim(required(f.encoding, "encoding", ctx)));
    e.gzip = encoding == "gzip" || encoding == "gz";
    if (!e.gzip && encoding != "raw") {
        throw InputError(ctx + ": unsupported encoding '" + encoding + "' (supported: raw, gzip)");
    }
    e.byteSkip = f.byteSkip ? parseIntField(*f.byteSkip, "byte skip", ctx) : 0;
    e.lineSkip = f.lineSkip ? parseIntField(*f.lineSkip, "line skip", ctx) : 0;
    if (e.byteSkip < -1 || e.byteSkip > static_cast<std::int64_t>(detail::kMaxBytes)) {
        throw InputError(ctx + ": invalid byte skip " + std::to_string(e.byteSkip));
    }
    if (e.byteSkip == -1 && e.gzip) {
        throw InputError(ctx + ": byte skip -1 is only valid with raw encoding");
    }
    if (e.lineSkip < 0) throw InputError(ctx + ": invalid line skip " + std::to_string(e.lineSkip));
    return e;
}

/// Where the voxel data is read from: after the header's blank line in `in`,
/// or a detached data file.
struct NrrdData {
    std::optional<InputFile> detached;
    std::istream* stream = nullptr;
    std::string ctx;
    std::uint64_t fileSize = 0;
};

void openData(NrrdData& d, const detail::NrrdFields& f, std::istream& in,
              std::uint64_t headerFileSize, bool endedByBlankLine, const std::string& ctx,
              const std::optional<std::filesystem::path>& dataFolder) {
    d.stream = &in;
    d.ctx = ctx;
    d.fileSize = headerFileSize;
    if (!f.dataFile) {
        if (!endedByBlankLine) {
            throw InputError(ctx + ": no data: the header has no blank line after it and no "
                                   "'data file' field");
        }
        return;
    }
    const std::string name(trim(*f.dataFile));
    if (name.rfind("LIST", 0) == 0 ||
        (name.find('%') != std::string::npos && name.find(' ') != std::string::npos)) {
        throw InputError(ctx + ": multi-file 'data file' lists are not supported ('" + name +
                         "'); use a single data file");
    }
    if (!dataFolder) {
        throw InputError(ctx + ": data file '" + name +
                         "' cannot be read: a header read from memory has no folder");
    }
    std::filesystem::path dataPath(name);
    if (dataPath.is_relative()) dataPath = *dataFolder / dataPath;
    d.detached.emplace(dataPath, "it",
                       ctx + ": data file '" + name + "' (" + dataPath.string() + ")");
    d.fileSize = d.detached->size();
    d.stream = &d.detached->stream();
    d.ctx = ctx + " (data file " + dataPath.string() + ")";
}

/// Reads a NRRD whose header starts at the beginning of `in` (`headerFileSize`
/// bytes in all). A detached data file is looked up in `dataFolder`; without
/// one (bytes in memory) a 'data file' field is an error.
Volume readNrrdStream(std::istream& in, std::uint64_t headerFileSize, const std::string& ctx,
                      const std::optional<std::filesystem::path>& dataFolder) {
    bool endedByBlankLine = false;
    const detail::NrrdFields f = readNrrdHeader(in, ctx, endedByBlankLine);
    const NrrdGrid grid = readGrid(f, ctx);
    Volume volume;
    volume.dims = glm::ivec3(static_cast<int>(grid.sizes[0]), static_cast<int>(grid.sizes[1]),
                             static_cast<int>(grid.sizes[2]));
    volume.type = grid.type;
    readGeometry(f, grid, volume, ctx);
    readScaling(f, volume, ctx);
    const NrrdEncoding encoding = readEncoding(f, ctx);

    NrrdData data;
    openData(data, f, in, headerFileSize, endedByBlankLine, ctx, dataFolder);
    std::size_t unused = std::numeric_limits<std::size_t>::max();
    std::string skipped;
    for (std::int64_t i = 0; i < encoding.lineSkip; ++i) {
        if (!readNrrdLine(*data.stream, skipped, unused, data.ctx)) {
            throw InputError(data.ctx + ": line skip " + std::to_string(encoding.lineSkip) +
                             " goes past the end of the file");
        }
    }
    const detail::VoxelSource source{data.stream, data.ctx, data.fileSize};
    volume.data = encoding.gzip
                      ? detail::readCompressedVoxels(source, encoding.byteSkip, grid.bytes)
                      : detail::readRawVoxels(source, encoding.byteSkip, grid.bytes);
    if (detail::needsSwap(encoding.bigEndian)) {
        detail::swapBytes(volume.data.data(), volume.voxelCount(), voxelSize(grid.type));
    }
    return volume;
}

} // namespace

Volume readNrrd(const std::filesystem::path& path) {
    InputFile file(path, "volume");
    return readNrrdStream(file.stream(), file.size(), path.string(), path.parent_path());
}

Volume readNrrdBytes(std::span<const std::byte> bytes, const std::string& name) {
    detail::MemoryBuffer buffer(bytes);
    std::istream in(&buffer);
    return readNrrdStream(in, bytes.size(), name, std::nullopt);
}

Volume readNrrdBytes(std::span<const std::byte> bytes, const std::string& name,
                     const std::filesystem::path& dataFolder) {
    detail::MemoryBuffer buffer(bytes);
    std::istream in(&buffer);
    return readNrrdStream(in, bytes.size(), name, dataFolder);
}

std::optional<std::filesystem::path> nrrdDataFile(const std::filesystem::path& path) {
    try {
        InputFile file(path, "volume");
        bool endedByBlankLine = false;
        const detail::NrrdFields f = readNrrdHeader(file.stream(), path.string(), endedByBlankLine);
        if (!f.dataFile) return std::nullopt;
        const std::filesystem::path data(std::string(trim(*f.dataFile)));
        return data.is_relative() ? path.parent_path() / data : data;
    } catch (const InputError&) {
        return std::nullopt; // reading the volume says what is wrong with it
    }
}

} // namespace cutaway
