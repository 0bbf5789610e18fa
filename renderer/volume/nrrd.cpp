// NRRD reader (http://teem.sourceforge.net/nrrd/format.html), NRRD0001..NRRD0005:
// attached (.nrrd) and detached (.nhdr + data file) headers, raw and gzip
// encodings, either byte order, 3D grids (or 4D with a first axis of size 1).
// Geometry from `space` (or `space dimension`), `space directions` and `space
// origin`, anatomical spaces converted to LPS (volume.hpp); else `spacings`.
#include "core/error.hpp"
#include "io/input_file.hpp"
#include "volume/byte_order.hpp"
#include "volume/gzip.hpp"
#include "volume/io_util.hpp"
#include "volume/nrrd_header.hpp"
#include "volume/volume.hpp"

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
        throw InputError(ctx + ": field '" + field + "' is not an integer: '" + text + "'");
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
                             " contradicts space '" + std::string(trim(*f.space)) + "'");
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

/// Reads a NRRD whose header starts at the beginning of `in` (`headerFileSize`
/// bytes in all). A detached data file is looked up in `dataFolder`; without
/// one (bytes in memory) a 'data file' field is an error.
Volume readNrrdStream(std::istream& in, std::uint64_t headerFileSize, const std::string& ctx,
                      const std::optional<std::filesystem::path>& dataFolder) {
    bool endedByBlankLine = false;
    const detail::NrrdFields f = readNrrdHeader(in, ctx, endedByBlankLine);

    const VoxelType type = parseNrrdType(required(f.type, "type", ctx), ctx);
    const std::int64_t dimension =
        parseIntField(required(f.dimension, "dimension", ctx), "dimension", ctx);
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
        const NrrdSpace space = parseSpace(f, ctx);
        const auto vectors = parseNrrdVectors(*f.directions, "space directions", ctx);
        if (static_cast<std::int64_t>(vectors.size()) != dimension) {
            throw InputError(ctx + ": 'space directions' has " + std::to_string(vectors.size()) +
                             " entries but dimension is " + std::to_string(dimension));
        }
        for (int a = 0; a < 3; ++a) {
            const auto& v = vectors[first + static_cast<std::size_t>(a)];
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
    } else {
        if (f.spacings) {
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
        // Without space directions the axes have no orientation in a space:
        // an origin is kept as written, for reference.
        if (f.origin) {
            const std::vector<double> origin = originVector(*f.origin, ctx);
            for (std::size_t a = 0; a < std::min<std::size_t>(3, origin.size()); ++a) {
                volume.origin[static_cast<int>(a)] = origin[a];
            }
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
        if (endian == "big")
            bigEndian = true;
        else if (endian != "little")
            throw InputError(ctx + ": unknown endian '" + *f.endian + "'");
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
    std::optional<InputFile> detached;
    std::istream* data = &in;
    std::string dataCtx = ctx;
    std::uint64_t dataFileSize = headerFileSize;
    if (f.dataFile) {
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
        detached.emplace(dataPath, "it",
                         ctx + ": data file '" + name + "' (" + dataPath.string() + ")");
        dataFileSize = detached->size();
        data = &detached->stream();
        dataCtx = ctx + " (data file " + dataPath.string() + ")";
    } else if (!endedByBlankLine) {
        throw InputError(ctx + ": no data: the header has no blank line after it and no 'data "
                               "file' field");
    }
    std::size_t unused = std::numeric_limits<std::size_t>::max();
    std::string skipped;
    for (std::int64_t i = 0; i < lineSkip; ++i) {
        if (!readNrrdLine(*data, skipped, unused, dataCtx)) {
            throw InputError(dataCtx + ": line skip " + std::to_string(lineSkip) +
                             " goes past the end of the file");
        }
    }

    if (!gzip) {
        auto start = static_cast<std::uint64_t>(data->tellg());
        if (byteSkip == -1) {
            // Data at the end of the file, whatever comes before it.
            if (dataFileSize < bytes)
                start = dataFileSize + 1;
            else
                start = dataFileSize - bytes;
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
        if (reader.skip(static_cast<std::uint64_t>(byteSkip)) <
            static_cast<std::uint64_t>(byteSkip)) {
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

std::vector<std::filesystem::path> volumeFiles(const std::filesystem::path& path) {
    std::vector<std::filesystem::path> files{path};
    const std::string name = detail::toLower(path.filename().string());
    if (!name.ends_with(".nrrd") && !name.ends_with(".nhdr")) return files;
    try {
        InputFile file(path, "volume");
        bool endedByBlankLine = false;
        const detail::NrrdFields f = readNrrdHeader(file.stream(), path.string(), endedByBlankLine);
        if (f.dataFile) {
            const std::filesystem::path data(std::string(trim(*f.dataFile)));
            files.push_back(data.is_relative() ? path.parent_path() / data : data);
        }
    } catch (const InputError&) {
        // Reading the volume says what is wrong with it.
    }
    return files;
}

} // namespace cutaway
