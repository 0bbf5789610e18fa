#pragma once
// A scalar volume on a regular grid, as read from disk or made by a phantom.
//
// Voxels are kept in their native type (a label volume with ids up to 12175
// stays int16; a uint8 CT stays one byte per voxel), x fastest, then y, then z,
// in host byte order. The physical value of voxel i is raw(i) * slope + inter
// (NIfTI scl_slope/scl_inter; 1 and 0 otherwise).
//
// Geometry: voxel (i, j, k) covers the cell [i, i+1] x [j, j+1] x [k, k+1] in
// index space; its centre is at (i + 0.5, ...). Physical extent in millimetres
// is dims * spacing. cutaway renders and deforms in the axis frame of the index
// grid (x along i, ...). Where the file is in the patient's (or scanner's)
// space is kept for writing it back: the centre of voxel (i, j, k) lies at
// origin + direction * (spacing * (i, j, k)) in `space` (physicalPosition).
// Anatomical spaces are all stored as LPS, the DICOM and ITK convention: a
// NIfTI's RAS sform/qform and a NRRD's RAS or LAS space are converted on
// reading.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cutaway {

enum class VoxelType { U8, I8, U16, I16, U32, I32, F32, F64 };

/// Bytes per voxel of a type.
std::size_t voxelSize(VoxelType type);
/// Canonical name: "uint8", "int8", "uint16", "int16", "uint32", "int32", "float32", "float64".
std::string_view voxelTypeName(VoxelType type);
/// The numbers a voxel type stores, lowest and highest (floats: their finite range).
std::pair<double, double> storedRange(VoxelType type);
/// Parses a canonical name (as above); throws InputError naming `context` otherwise.
VoxelType parseVoxelType(std::string_view name, std::string_view context);

/// The space a volume's origin and direction are expressed in.
enum class Space {
    None,         ///< the file said nothing of one (phantoms, raw files, NRRD with
                  ///< `spacings` only, NIfTI with neither qform nor sform)
    LPS,          ///< anatomical: x to the patient's left, y posterior, z superior
    NonAnatomical ///< a 3D space with no anatomical meaning (NRRD scanner-xyz,
                  ///< 3D-right-handed, 3D-left-handed, `space dimension: 3`)
};

struct Volume {
    glm::ivec3 dims{0};      ///< voxels along x, y, z; each >= 1
    glm::dvec3 spacing{1.0}; ///< millimetres between voxel centres, each > 0 and finite
    glm::dvec3 origin{0.0};  ///< position of voxel (0,0,0)'s centre in `space`
    /// Column a: the unit vector along which index axis a runs in `space`
    /// (direction cosines; identity when the file gave none).
    glm::dmat3 direction{1.0};
    Space space = Space::None;
    VoxelType type = VoxelType::U8;
    double slope = 1.0; ///< value = raw * slope + inter
    double inter = 0.0;
    std::vector<std::byte> data; ///< voxelCount() * voxelSize(type) bytes
    /// NIfTI's qform_code and sform_code as the file gave them (1 scanner,
    /// 2 aligned, 3 Talairach, 4 MNI, 5 template), when it was NIfTI with a
    /// placement: an export writes them again. None for other formats.
    std::optional<std::array<int, 2>> niftiCodes;

    std::size_t voxelCount() const;
    std::size_t index(int x, int y, int z) const; ///< x + dims.x * (y + dims.y * z)
    double raw(std::size_t i) const;              ///< the stored number, converted to double
    /// Stores `value` as voxel i's number (in the type's range, whole for an
    /// integer type: see storedRange).
    void setRaw(std::size_t i, double value);
    double value(std::size_t i) const { return raw(i) * slope + inter; }
    double value(int x, int y, int z) const { return value(index(x, y, z)); }
    glm::dvec3 extent() const { return glm::dvec3(dims) * spacing; } ///< millimetres
    /// Where the centre of voxel `voxel` (fractional indices allowed) lies in
    /// `space`: origin + direction * (spacing * voxel).
    glm::dvec3 physicalPosition(glm::dvec3 voxel) const {
        return origin + direction * (spacing * voxel);
    }
    /// Whether the volume has a place in a space: anything a NRRD writes as
    /// `space`/`space dimension`, `space directions` and `space origin`.
    bool hasPhysicalPlacement() const {
        return space != Space::None || origin != glm::dvec3(0.0) || direction != glm::dmat3(1.0);
    }

    /// Allocates zeroed storage for the given shape and type.
    static Volume allocate(glm::ivec3 dims, VoxelType type, glm::dvec3 spacing = glm::dvec3(1.0));
};

/// Minimum and maximum physical value of the finite voxels (NaN and infinite
/// ones are left out; a volume with none finite gives {0, 0}).
struct ValueRange {
    double min = 0.0;
    double max = 0.0;
};
ValueRange valueRange(const Volume& volume);

/// How many voxels are NaN or infinite (only floating-point volumes hold such).
std::size_t nonFiniteCount(const Volume& volume);

/// Gives every NaN or infinite voxel the physical value `value`; returns how many.
std::size_t replaceNonFinite(Volume& volume, double value);

/// Layout of a headerless raw file.
struct RawLayout {
    glm::ivec3 dims{0};
    VoxelType type = VoxelType::U8;
    glm::dvec3 spacing{1.0};
    bool bigEndian = false;
    std::uint64_t offset = 0; ///< bytes to skip before the first voxel
    bool operator==(const RawLayout&) const = default;
};

/// Reads .nrrd/.nhdr, .nii/.nii.gz, .mha/.mhd by extension, and DICOM
/// (volume/dicom.hpp). Throws InputError naming the
/// file and the problem (missing file, bad header, truncated data, ...).
Volume readVolume(const std::filesystem::path& path);
Volume readNrrd(const std::filesystem::path& path);
Volume readNifti(const std::filesystem::path& path);
/// MetaImage: .mha (attached data) or .mhd (ElementDataFile names the data).
Volume readMetaImage(const std::filesystem::path& path);
Volume readRaw(const std::filesystem::path& path, const RawLayout& layout);
/// The files reading the volume `path` reads: the file itself and, for a
/// detached NRRD or MetaImage header, its data file; for DICOM, the folder or
/// DICOMDIR and every file of its series. A header that cannot be read gives
/// the file alone (reading it then says what is wrong).
std::vector<std::filesystem::path> volumeFiles(const std::filesystem::path& path);
/// The data file a detached header names (nullopt: attached, or unreadable).
std::optional<std::filesystem::path> nrrdDataFile(const std::filesystem::path& path);
std::optional<std::filesystem::path> metaImageDataFile(const std::filesystem::path& path);
/// The NRRD and NIfTI readers over a file's bytes already in memory (not
/// copied); `name` stands for the file in messages. A NRRD header read this way
/// cannot name a detached data file (there is no folder to find it in).
Volume readNrrdBytes(std::span<const std::byte> bytes, const std::string& name);
/// A detached NRRD header's bytes, its data file looked up in `dataFolder`
/// (read as readNrrd reads it: io/input_file.hpp).
Volume readNrrdBytes(std::span<const std::byte> bytes, const std::string& name,
                     const std::filesystem::path& dataFolder);
Volume readNiftiBytes(std::span<const std::byte> bytes, const std::string& name);
/// A MetaImage header with its data attached (ElementDataFile = LOCAL).
Volume readMetaImageBytes(std::span<const std::byte> bytes, const std::string& name);

/// Writes an attached-header NRRD (raw or gzip encoding), native voxel type,
/// little endian. A volume with a place in a space (hasPhysicalPlacement) gets
/// `space: left-posterior-superior` (Space::LPS) or `space dimension: 3`,
/// `space directions` (direction columns times spacing) and `space origin`;
/// any other gets `spacings`. Written to a temporary name, then renamed.
void writeNrrd(const std::filesystem::path& path, const Volume& volume, bool gzip = true);
/// Writes NIfTI-1 (.nii; .nii.gz gzip-compressed), little endian, the native
/// voxel type and slope/intercept. A volume in patient coordinates
/// (Space::LPS) gets its affine, in NIfTI's RAS, as sform and qform (codes
/// 1); any other the spacing alone. Written to a temporary name, then renamed.
void writeNifti(const std::filesystem::path& path, const Volume& volume);

} // namespace cutaway
