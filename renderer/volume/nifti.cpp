// NIfTI-1 and NIfTI-2 single-file reader (.nii, .nii.gz; magic "n+1", "n+2"),
// either byte order.
// Geometry from the sform, else the qform, converted from RAS to LPS (volume.hpp).
// https://nifti.nimh.nih.gov/nifti-1/documentation/nifti1fields
#include "core/error.hpp"
#include "io/input_file.hpp"
#include "volume/byte_order.hpp"
#include "volume/gzip.hpp"
#include "volume/io_util.hpp"
#include "volume/volume.hpp"

#include <cmath>
#include <cstring>
#include <optional>
#include <utility>

namespace cutaway {

namespace {

constexpr std::size_t kHeader1 = 348;
constexpr std::size_t kHeader2 = 540;
/// vox_offset beyond this is not a real file (it would mean a gigabyte of
/// header extensions); refusing it keeps a hostile .nii.gz from making us
/// inflate gigabytes just to find the data.
constexpr double kMaxVoxOffset = double(std::uint64_t{1} << 30);

/// Where NIfTI-1 and NIfTI-2 keep the fields read here: NIfTI-2 widens the
/// integers to 64 bits (codes to 32) and the reals to doubles, and moves them.
struct Layout {
    std::size_t size;     ///< sizeof_hdr
    bool wide;            ///< NIfTI-2
    std::size_t datatype; ///< int16 in both
    std::size_t dim, pixdim, voxOffset, slope, inter;
    std::size_t qformCode, sformCode, quatern, qoffset, srow;
};
constexpr Layout kNifti1{kHeader1, false, 70, 40, 76, 108, 112, 116, 252, 254, 256, 268, 280};
constexpr Layout kNifti2{kHeader2, true, 12, 16, 104, 168, 176, 184, 344, 348, 352, 376, 400};

/// Field access on the raw header bytes, converting from the file's byte
/// order and widths (Layout).
class HeaderBytes {
public:
    HeaderBytes(const std::byte* bytes, bool swap, const Layout& layout)
        : m_bytes(bytes), m_swap(swap), m_layout(layout) {}

    template <typename T>
    T get(std::size_t offset) const {
        std::byte copy[sizeof(T)];
        std::memcpy(copy, m_bytes + offset, sizeof(T));
        if (m_swap) detail::swapBytes(copy, 1, sizeof(T));
        T value;
        std::memcpy(&value, copy, sizeof(T));
        return value;
    }
    std::int16_t i16(std::size_t offset) const { return get<std::int16_t>(offset); }
    /// dim[i] (int16, NIfTI-2 int64).
    std::int64_t dim(std::size_t i) const {
        return m_layout.wide ? get<std::int64_t>(m_layout.dim + 8 * i) : i16(m_layout.dim + 2 * i);
    }
    /// A code (qform_code, sform_code: int16, NIfTI-2 int32).
    std::int32_t code(std::size_t offset) const {
        return m_layout.wide ? get<std::int32_t>(offset) : i16(offset);
    }
    /// The i-th real from `offset` (float, NIfTI-2 double).
    double real(std::size_t offset, std::size_t i = 0) const {
        return m_layout.wide ? get<double>(offset + 8 * i) : get<float>(offset + 4 * i);
    }
    const Layout& layout() const { return m_layout; }

private:
    const std::byte* m_bytes;
    bool m_swap;
    Layout m_layout;
};

VoxelType niftiType(std::int16_t code, const std::string& ctx) {
    switch (code) {
    case 2:
        return VoxelType::U8;
    case 4:
        return VoxelType::I16;
    case 8:
        return VoxelType::I32;
    case 16:
        return VoxelType::F32;
    case 64:
        return VoxelType::F64;
    case 256:
        return VoxelType::I8;
    case 512:
        return VoxelType::U16;
    case 768:
        return VoxelType::U32;
    default:
        break;
    }
    const char* name = "unknown";
    switch (code) {
    case 1:
        name = "binary";
        break;
    case 32:
        name = "complex64";
        break;
    case 128:
        name = "RGB24";
        break;
    case 1024:
        name = "int64";
        break;
    case 1280:
        name = "uint64";
        break;
    case 1536:
        name = "float128";
        break;
    case 1792:
        name = "complex128";
        break;
    case 2048:
        name = "complex256";
        break;
    case 2304:
        name = "RGBA32";
        break;
    default:
        break;
    }
    throw InputError(ctx + ": unsupported NIfTI datatype " + std::to_string(code) + " (" + name +
                     "); cutaway reads uint8, int8, uint16, int16, uint32, int32, float32 and "
                     "float64");
}

/// Where the voxel grid lies in NIfTI's RAS space: unit direction columns
/// (index axis a is column a) and the position of voxel (0,0,0)'s centre.
struct Placement {
    glm::dmat3 direction{1.0};
    glm::dvec3 origin{0.0};
};

bool finite(glm::dvec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// The columns of `m` normalised, with `origin`; nothing when one is not
/// finite or has no length.
std::optional<Placement> normalised(glm::dmat3 m, glm::dvec3 origin) {
    if (!finite(origin)) return std::nullopt;
    for (int a = 0; a < 3; ++a) {
        const double length = glm::length(m[a]);
        if (!finite(m[a]) || !std::isfinite(length) || length <= 0.0) return std::nullopt;
        m[a] /= length;
    }
    return Placement{m, origin};
}

/// Method 3: the affine of srow_x, srow_y, srow_z.
std::optional<Placement> sformPlacement(const HeaderBytes& h) {
    const std::size_t srow = h.layout().srow, rowLength = h.layout().wide ? 32 : 16;
    glm::dmat3 m(1.0);
    glm::dvec3 origin(0.0);
    for (std::size_t row = 0; row < 3; ++row) {
        for (std::size_t col = 0; col < 3; ++col)
            m[static_cast<int>(col)][static_cast<int>(row)] = h.real(srow + rowLength * row, col);
        origin[static_cast<int>(row)] = h.real(srow + rowLength * row, 3);
    }
    return normalised(m, origin);
}

/// Method 2: the rotation of the quaternion (b, c, d), its third column
/// negated when qfac (pixdim[0]) is negative, and qoffset.
std::optional<Placement> qformPlacement(const HeaderBytes& h) {
    const std::size_t q = h.layout().quatern, o = h.layout().qoffset;
    double b = h.real(q, 0), c = h.real(q, 1), d = h.real(q, 2);
    if (!std::isfinite(b) || !std::isfinite(c) || !std::isfinite(d)) return std::nullopt;
    double a = 1.0 - (b * b + c * c + d * d);
    if (a < 1.0e-7) {
        // Not quite a unit quaternion: a 180 degree rotation (as nifti1_io does).
        const double norm = std::sqrt(b * b + c * c + d * d);
        if (norm == 0.0) return std::nullopt;
        b /= norm;
        c /= norm;
        d /= norm;
        a = 0.0;
    } else {
        a = std::sqrt(a);
    }
    // glm: m[column][row].
    glm::dmat3 r;
    r[0] = {a * a + b * b - c * c - d * d, 2 * (b * c + a * d), 2 * (b * d - a * c)};
    r[1] = {2 * (b * c - a * d), a * a + c * c - b * b - d * d, 2 * (c * d + a * b)};
    r[2] = {2 * (b * d + a * c), 2 * (c * d - a * b), a * a + d * d - c * c - b * b};
    if (h.real(h.layout().pixdim) < 0.0) r[2] = -r[2]; // qfac
    return normalised(r, glm::dvec3(h.real(o, 0), h.real(o, 1), h.real(o, 2)));
}

struct Parsed {
    Volume volume;            ///< everything but the data
    std::size_t bytes = 0;    ///< voxel data size
    std::uint64_t offset = 0; ///< where the data starts
    bool swap = false;
};

/// Which header `first4` (the file's first 4 bytes, sizeof_hdr) begins, and
/// whether its byte order is the other one. Throws for neither.
std::pair<const Layout*, bool> layoutOf(const std::byte* first4, const std::string& ctx) {
    std::int32_t asWritten = 0, swapped = 0;
    std::memcpy(&asWritten, first4, 4);
    swapped = asWritten;
    detail::swapBytes(reinterpret_cast<std::byte*>(&swapped), 1, 4);
    for (const Layout* l : {&kNifti1, &kNifti2}) {
        if (asWritten == std::int32_t(l->size)) return {l, false};
        if (swapped == std::int32_t(l->size)) return {l, true}; // the other byte order
    }
    throw InputError(ctx + ": not a NIfTI file (sizeof_hdr is " + std::to_string(asWritten) +
                     ", expected 348 for NIfTI-1 or 540 for NIfTI-2)");
}

void checkMagic(const std::byte* raw, const Layout& l, const std::string& ctx) {
    if (!l.wide && std::memcmp(raw + 344, "ni1\0", 4) == 0)
        throw InputError(ctx + ": a NIfTI-1 header-only file (magic ni1, data in a separate .img) "
                               "is not supported; use a single .nii");
    if (l.wide && std::memcmp(raw + 4, "ni2\0", 4) == 0)
        throw InputError(ctx + ": a NIfTI-2 header-only file (magic ni2, data in a separate .img) "
                               "is not supported; use a single .nii");
    if (!l.wide && std::memcmp(raw + 344, "n+1\0", 4) != 0)
        throw InputError(ctx + ": not a NIfTI-1 file (bad magic, expected \"n+1\")");
    if (l.wide && std::memcmp(raw + 4, "n+2\0\r\n\032\n", 8) != 0)
        throw InputError(ctx + ": not a NIfTI-2 file (bad magic, expected \"n+2\")");
}

/// dim[]: a single 3D volume, each size >= 1; its voxel data's size.
std::size_t readDims(const HeaderBytes& h, Volume& v, const std::string& ctx) {
    const std::int64_t rank = h.dim(0);
    if (rank < 1 || rank > 7) {
        throw InputError(ctx + ": dim[0] is " + std::to_string(rank) + " (must be 1..7)");
    }
    if (rank < 3) {
        throw InputError(ctx + ": the image is " + std::to_string(rank) +
                         "-dimensional; cutaway reads 3D volumes");
    }
    for (std::size_t d = 4; d <= std::size_t(rank); ++d) {
        if (h.dim(d) != 1) {
            throw InputError(ctx + ": dim[" + std::to_string(d) + "] is " +
                             std::to_string(h.dim(d)) +
                             "; cutaway reads a single 3D volume (time series and vectors are not "
                             "supported)");
        }
    }
    v.type = niftiType(h.i16(h.layout().datatype), ctx);
    std::int64_t sizes[3] = {};
    for (std::size_t a = 0; a < 3; ++a) {
        sizes[a] = h.dim(a + 1);
        if (sizes[a] < 1) {
            throw InputError(ctx + ": dim[" + std::to_string(a + 1) + "] is " +
                             std::to_string(sizes[a]) + " (must be >= 1)");
        }
    }
    const std::size_t bytes = detail::checkedByteCount(sizes, v.type, ctx);
    v.dims = glm::ivec3(static_cast<int>(sizes[0]), static_cast<int>(sizes[1]),
                        static_cast<int>(sizes[2]));
    return bytes;
}

/// Spacing, scaling and placement.
void readGeometry(const HeaderBytes& h, Volume& v, const std::string& ctx) {
    const Layout& l = h.layout();
    for (int a = 0; a < 3; ++a) {
        // pixdim may be negative (a flip: only the magnitude is spacing) or 0
        // (written by many tools when unknown: taken as 1 mm).
        double spacing = std::fabs(h.real(l.pixdim, std::size_t(a) + 1));
        if (spacing == 0.0) spacing = 1.0;
        detail::checkSpacing(spacing, a, ctx);
        v.spacing[a] = spacing;
    }
    // Scaling: slope 0 or not finite means none (as the NIfTI standard says).
    const double slope = h.real(l.slope), inter = h.real(l.inter);
    if (std::isfinite(slope) && slope != 0.0) {
        v.slope = slope;
        v.inter = std::isfinite(inter) ? inter : 0.0;
    }
    // Orientation: the sform if set, else the qform (NIfTI's methods 3 and 2);
    // neither (or one that is not finite or has a zero axis): none.
    std::optional<Placement> placement;
    if (h.code(l.sformCode) > 0) placement = sformPlacement(h);
    if (!placement && h.code(l.qformCode) > 0) placement = qformPlacement(h);
    if (placement) {
        // NIfTI's space is RAS; LPS negates x and y.
        const glm::dmat3 toLps(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1));
        v.direction = toLps * placement->direction;
        v.origin = toLps * placement->origin;
        v.space = Space::LPS;
        v.niftiCodes = std::array<int, 2>{int(h.code(l.qformCode)), int(h.code(l.sformCode))};
    }
}

/// The header in `raw` (its layout's size of bytes).
Parsed parseHeader(const std::byte* raw, const Layout& layout, bool swap, const std::string& ctx) {
    checkMagic(raw, layout, ctx);
    const HeaderBytes h(raw, swap, layout);
    Parsed p;
    p.swap = swap;
    p.bytes = readDims(h, p.volume, ctx);
    const double voxOffset =
        layout.wide ? double(h.get<std::int64_t>(layout.voxOffset)) : h.real(layout.voxOffset);
    if (!std::isfinite(voxOffset) || voxOffset < 0.0 || voxOffset > kMaxVoxOffset) {
        throw InputError(ctx + ": invalid vox_offset " + detail::formatDouble(voxOffset));
    }
    // A single file's data cannot start inside the header; old writers left 0 here.
    p.offset = std::max<std::uint64_t>(layout.size + 4, static_cast<std::uint64_t>(voxOffset));
    readGeometry(h, p.volume, ctx);
    return p;
}

/// Whether `in` starts with the gzip magic; leaves it at its start.
bool isGzip(std::istream& in) {
    unsigned char magic[2] = {};
    in.read(reinterpret_cast<char*>(magic), 2);
    const bool gzip = in.gcount() == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
    in.clear();
    in.seekg(0);
    return gzip;
}

std::string tooShort(const Layout& l, std::uint64_t got, const char* after,
                     const std::string& ctx) {
    return ctx + ": too short for a NIfTI-" + (l.wide ? "2" : "1") + " header (" +
           std::to_string(got) + " bytes" + after + ", need " + std::to_string(l.size) + ")";
}

/// The header from a gzip stream, then exactly its data.
Parsed readGzipped(detail::GzipReader& reader, const std::string& ctx) {
    std::byte raw[kHeader2] = {};
    if (reader.read(raw, 4) < 4) throw InputError(ctx + ": too short for a NIfTI header");
    const auto [layout, swap] = layoutOf(raw, ctx);
    const std::size_t got = 4 + reader.read(raw + 4, layout->size - 4);
    if (got < layout->size) throw InputError(tooShort(*layout, got, " after decompression", ctx));
    Parsed p = parseHeader(raw, *layout, swap, ctx);
    const std::uint64_t gap = p.offset - layout->size;
    if (reader.skip(gap) < gap) {
        throw InputError(ctx + ": vox_offset " + std::to_string(p.offset) +
                         " is beyond the end of the file (" + std::to_string(reader.position()) +
                         " bytes after decompression)");
    }
    p.volume.data = detail::readUpTo(reader, p.bytes);
    if (p.volume.data.size() < p.bytes) {
        throw InputError(ctx + ": data truncated: expected " + std::to_string(p.bytes) +
                         " bytes after vox_offset " + std::to_string(p.offset) + ", found " +
                         std::to_string(p.volume.data.size()));
    }
    std::byte extra{};
    if (reader.read(&extra, 1) != 0) {
        throw InputError(ctx + ": decompressed data exceeds the declared size (" +
                         std::to_string(p.offset + p.bytes) + " bytes)");
    }
    return p;
}

/// The header and the data of an uncompressed file of `fileSize` bytes.
Parsed readPlain(std::istream& in, std::uint64_t fileSize, const std::string& ctx) {
    std::byte raw[kHeader2] = {};
    if (fileSize < 4) throw InputError(tooShort(kNifti1, fileSize, "", ctx));
    detail::readSome(in, raw, 4);
    const auto [layout, swap] = layoutOf(raw, ctx);
    if (fileSize < layout->size) throw InputError(tooShort(*layout, fileSize, "", ctx));
    detail::readSome(in, raw + 4, layout->size - 4);
    Parsed p = parseHeader(raw, *layout, swap, ctx);
    if (p.offset > fileSize) {
        throw InputError(ctx + ": vox_offset " + std::to_string(p.offset) +
                         " is beyond the end of the file (" + std::to_string(fileSize) + " bytes)");
    }
    const std::uint64_t available = fileSize - p.offset;
    if (available < p.bytes) {
        throw InputError(ctx + ": data truncated: expected " + std::to_string(p.bytes) +
                         " bytes after vox_offset " + std::to_string(p.offset) + ", found " +
                         std::to_string(available));
    }
    in.seekg(static_cast<std::streamoff>(p.offset));
    p.volume.data.resize(p.bytes);
    if (detail::readSome(in, p.volume.data.data(), p.bytes) != p.bytes) {
        throw InputError(ctx + ": read error in the voxel data");
    }
    return p;
}

/// Reads a .nii or .nii.gz from the start of `in` (`fileSize` bytes).
Volume readNiftiStream(std::istream& in, std::uint64_t fileSize, const std::string& ctx) {
    Parsed p;
    // Sniff the content rather than trust the extension: a .nii may be gzipped.
    if (isGzip(in)) {
        detail::GzipReader reader(in, ctx);
        p = readGzipped(reader, ctx);
    } else {
        p = readPlain(in, fileSize, ctx);
    }
    if (p.swap) {
        detail::swapBytes(p.volume.data.data(), p.volume.voxelCount(), voxelSize(p.volume.type));
    }
    return std::move(p.volume);
}

} // namespace

Volume readNifti(const std::filesystem::path& path) {
    InputFile file(path, "volume");
    return readNiftiStream(file.stream(), file.size(), path.string());
}

Volume readNiftiBytes(std::span<const std::byte> bytes, const std::string& name) {
    detail::MemoryBuffer buffer(bytes);
    std::istream in(&buffer);
    return readNiftiStream(in, bytes.size(), name);
}

} // namespace cutaway
