// The /volume and /transfer sections of a scene document.
#include "io/input_file.hpp"
#include "scene/scene_sections.hpp"
#include "volume/dicom.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <string>
#include <sys/stat.h>
#include <system_error>

namespace cutaway::scene_detail {

namespace {

// The phantom names of makePhantom (volume/phantom.hpp, phantomNames()). They
// are repeated here so that the scene library does not need the volume
// library's code at link time; keep the two lists in step.
constexpr std::string_view kHead = "head";
constexpr std::string_view kOrange = "orange";

// Voxel type names as in volume.hpp's voxelTypeName(), parsed here for the same reason.
struct VoxelTypeName {
    std::string_view name;
    VoxelType type;
};
constexpr VoxelTypeName kVoxelTypes[] = {
    {"uint8", VoxelType::U8},    {"int8", VoxelType::I8},     {"uint16", VoxelType::U16},
    {"int16", VoxelType::I16},   {"uint32", VoxelType::U32},  {"int32", VoxelType::I32},
    {"float32", VoxelType::F32}, {"float64", VoxelType::F64},
};

/// Whether readVolume() knows the file's format from its name.
bool hasVolumeExtension(const std::filesystem::path& path) {
    std::string name = path.filename().string();
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const std::string_view suffix : {".nrrd", ".nhdr", ".nii", ".nii.gz", ".mha", ".mhd"}) {
        if (name.size() > suffix.size() && name.ends_with(suffix)) return true;
    }
    return false;
}

/// /volume/raw: the layout of a headerless file.
///
///  * dims     [integer x3], voxels, each in [1, 65536], required
///             Voxels along x, y, z (x fastest in the file).
///  * type     string, required: "uint8", "int8", "uint16", "int16", "uint32",
///             "int32", "float32" or "float64"
///  * spacing  [number x3], mm, each in (0, 10000], default [1, 1, 1]
///  * endian   string, "little" or "big", default "little"
///  * offset   integer, bytes, >= 0, default 0: bytes to skip before the first voxel
RawLayout parseRaw(JsonReader& reader) {
    RawLayout raw;
    if (const auto dims = reader.integers("dims", 3, 3, 1, 65536, true))
        raw.dims = glm::ivec3(int((*dims)[0]), int((*dims)[1]), int((*dims)[2]));
    const auto type = reader.string(
        "type", {"uint8", "int8", "uint16", "int16", "uint32", "int32", "float32", "float64"},
        true);
    for (const VoxelTypeName& entry : kVoxelTypes) {
        if (type && *type == entry.name) raw.type = entry.type;
    }
    raw.spacing = reader.vec3("spacing", raw.spacing, Range::closed(1e-9, 1.0e4));
    raw.bigEndian = reader.string("endian", "little", {"little", "big"}) == "big";
    raw.offset = static_cast<std::uint64_t>(
        reader.integer("offset", 0, 0, std::numeric_limits<std::int64_t>::max()));
    return raw;
}

/// /volume/series: which series of a DICOM folder (string or integer: its
/// number, UID or description). Only with a DICOM `file`.
void parseSeries(JsonReader& reader, VolumeSource& volume, bool dicom) {
    const nlohmann::json* series = reader.find("series");
    if (!series) return;
    if (!dicom) {
        reader.error("series", "only allowed with a DICOM file, folder or DICOMDIR as \"file\"");
    } else if (series->is_string() && !series->get<std::string>().empty()) {
        volume.series = series->get<std::string>();
    } else if (series->is_number_integer() && series->get<std::int64_t>() >= 0) {
        volume.series = std::to_string(series->get<std::int64_t>());
    } else {
        reader.expected(reader.pointerOf("series"),
                        "a series number (integer >= 0), UID or description (a non-empty string)",
                        *series);
    }
}

} // namespace

std::filesystem::path readExistingFile(JsonReader& reader, std::string_view key,
                                       const std::filesystem::path& baseDir, bool folders) {
    const auto file = reader.string(key);
    if (!file) return {};
    // No file has such a name: the system would look up a shorter one, or none.
    if (file->find('\0') != std::string::npos || file->size() >= PATH_MAX) {
        reader.expected(reader.pointerOf(key),
                        "a path without NUL characters, of fewer than " + std::to_string(PATH_MAX) +
                            " bytes",
                        *reader.find(key));
        return {};
    }
    const std::filesystem::path path = (baseDir / *file).lexically_normal();
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0)
        reader.error(key, "no such file: " + path.string());
    else if (folders && S_ISDIR(status.st_mode))
        return path;
    else if (const char* kind = nonRegularKind(status.st_mode))
        reader.error(key, std::string("not a regular file (it is ") + kind + "): " + path.string());
    return path;
}

/// /volume: where the scalar field comes from. Exactly one of `file` or
/// `phantom` is required.
///
///  * file     string, path, required unless `phantom` is given
///             A .nrrd, .nhdr, .nii, .nii.gz, .mha or .mhd file, a DICOM folder, DICOMDIR
///             or file of a series (volume/dicom.hpp), or a headerless file
///             laid out as `raw` says. Relative paths are relative to the
///             scene file's folder. The file must exist.
///  * series   string or integer, default none: the DICOM series to read (its
///             number, UID or description). Only with a DICOM `file`.
///  * phantom  string, "head" or "orange", required unless `file` is given
///             A built-in procedural volume (uint8 values, 1 mm voxels).
///  * size     [integer x3], voxels, each in [8, 1024], default [128, 128, 128]
///             The phantom's grid. Only with `phantom`.
///  * raw      object, default none: the layout of a headerless file (see
///             parseRaw above). Only with `file`.
///  * spacing  [number x3], mm, each in (0, 10000], default: the file's (phantoms: 1 mm)
///             Overrides the voxel spacing.
///  * window   [number, number], volume values, lo < hi, each in [-1e30, 1e30],
///             default: none (the volume's value range)
///             The range of values of interest.
void parseVolume(JsonReader& reader, VolumeSource& volume, const std::filesystem::path& baseDir) {
    const bool hasFile = reader.has("file");
    const bool hasPhantom = reader.has("phantom");
    if (hasFile == hasPhantom) {
        reader.errorHere(std::string("expected exactly one of \"file\" or \"phantom\", got ") +
                         (hasFile ? "both" : "neither"));
    }

    volume.file = readExistingFile(reader, "file", baseDir, !reader.has("raw"));
    std::error_code ec; // a name the system refuses (too long, ...) was reported just above
    // A missing file was reported just above: its series is not refused too.
    const bool dicom = !volume.file.empty() && !reader.has("raw") &&
                       (isDicomPath(volume.file) || !std::filesystem::exists(volume.file, ec));
    if (!volume.file.empty() && std::filesystem::is_regular_file(volume.file, ec)) {
        if (!reader.has("raw") && !hasVolumeExtension(volume.file) && !dicom) {
            reader.expected(reader.pointerOf("file"),
                            "a .nrrd, .nhdr, .nii, .nii.gz, .mha or .mhd file, a DICOM file, "
                            "folder or DICOMDIR, or a \"raw\" layout for a headerless file",
                            *reader.find("file"));
        }
    }
    parseSeries(reader, volume, dicom);
    if (const auto phantom = reader.string("phantom", {kHead, kOrange})) volume.phantom = *phantom;

    if (reader.has("size") && hasFile && !hasPhantom) {
        reader.error("size", "only allowed with \"phantom\" (a file's grid comes from the file)");
    } else if (const auto size = reader.integers("size", 3, 3, 8, 1024)) {
        volume.phantomSize = glm::ivec3(int((*size)[0]), int((*size)[1]), int((*size)[2]));
    }
    if (reader.has("raw") && hasPhantom && !hasFile) {
        reader.error("raw", "only allowed with \"file\"");
    } else {
        reader.object("raw", [&](JsonReader& raw) { volume.raw = parseRaw(raw); });
    }

    volume.spacing = reader.vec3("spacing", Range::closed(1e-9, 1.0e4));
    if (const auto window = reader.numbers("window", 2, 2, Range::closed(-kMaxValue, kMaxValue))) {
        if ((*window)[0] < (*window)[1]) {
            volume.window = std::array<double, 2>{(*window)[0], (*window)[1]};
        } else {
            reader.expected(reader.pointerOf("window"), "[lo, hi] with lo < hi",
                            *reader.find("window"));
        }
    }
}

/// /transfer: the transfer function, piecewise linear between its points.
///
///  * points   array of at least 2 objects, required
///             Control points in order of strictly increasing `value`. Below
///             the first point the first point's colour and opacity apply,
///             above the last point the last's.
///    * value  number, volume value (after slope/intercept), in [-1e30, 1e30], required
///    * color  [number x3], linear RGB, each in [0, 1], required
///    * alpha  number, in [0, 1], required
///             Opacity of a sample one reference step thick (unit_distance);
///             the renderer corrects it for the slice spacing.
///  * unit_distance number, mm, in (0, 1e6], default the volume's smallest
///             voxel spacing: the thickness every alpha (and each label's) is
///             the opacity of; read in parseScene, beside labels.
///
/// Without a /transfer section: defaultTransfer(), a grey ramp from
/// transparent at 0 to alpha 0.6 at 255 (suits 8-bit data).
void parseTransfer(JsonReader& reader, TransferFunction& transfer) {
    transfer.points.clear();
    std::optional<double> previous;
    reader.objects(
        "points", 2, std::numeric_limits<std::size_t>::max(),
        [&](JsonReader& point, std::size_t) {
            TransferPoint result;
            const auto value = point.number("value", Range::closed(-kMaxValue, kMaxValue), true);
            if (value && previous && !(*value > *previous)) {
                point.expected(point.pointerOf("value"),
                               "a value greater than the previous point's (" +
                                   formatNumber(*previous) + ")",
                               *point.find("value"));
            }
            previous = value;
            result.value = value.value_or(0.0);
            result.color = point.colour("color", true).value_or(result.color);
            result.alpha =
                float(point.number("alpha", Range::closed(0.0, 1.0), true).value_or(0.0));
            transfer.points.push_back(result);
        },
        true);
}

TransferFunction defaultTransfer() {
    TransferFunction transfer;
    transfer.points = {
        TransferPoint{0.0, glm::vec3(0.9f), 0.0f},
        TransferPoint{255.0, glm::vec3(0.9f), 0.6f},
    };
    return transfer;
}

} // namespace cutaway::scene_detail
