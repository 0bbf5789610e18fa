#pragma once
// DICOM series, read through GDCM (the field's maintained DICOM library; of
// our own only a walk over the element headers that refuses a declared
// length past the file's end before GDCM allocates it: dicom_lengths.hpp). A volume may be named as a folder of DICOM files
// (searched recursively), a DICOMDIR (the folder it indexes) or one file of
// a series (the series it belongs to, from the files beside it).
//
// Geometry: slices are ordered by ImagePositionPatient along the slice
// normal (ImageOrientationPatient's row x column direction), never by file
// name or InstanceNumber; the slice spacing comes from those positions, not
// from SliceThickness. The volume's direction columns are the row direction,
// the column direction and the normal, its origin the first slice's position,
// its space LPS (DICOM's patient space). RescaleSlope/Intercept become the
// volume's slope and intercept (the same for every slice), or the values are
// rescaled to float32 (slopes that differ between slices).
//
// Refused, with a message naming the file or the slices: uneven slice
// spacing, missing slices, a gantry tilt (positions not along the normal),
// slices of different sizes, orientations, spacings or pixel types, two
// slices at one position, multi-frame or colour images, and pixel data GDCM
// cannot decode. Files that are not DICOM images (a DICOMDIR, a text file, a
// report) are passed over and counted.
//
// GDCM parses in a child process: a file on which it aborts (a header cut
// short) is refused naming the file. Folders are walked without following
// symbolic links to folders (a link to a parent would loop) or to files
// outside the folder.
#include "volume/volume.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace cutaway {

/// One series found among a folder's files.
struct DicomSeries {
    std::string uid;         ///< SeriesInstanceUID
    std::string number;      ///< SeriesNumber as written ("" when absent)
    std::string description; ///< SeriesDescription ("" when absent)
    std::string modality;    ///< Modality ("" when absent)
    glm::ivec3 dims{0};      ///< columns x rows x slices (files)
    int bitsAllocated = 0;   ///< BitsAllocated of its first file (0 when absent)
    std::vector<std::filesystem::path> files;
};

/// What a DICOM path holds: its series (ordered by number, then UID), how
/// many files were passed over, and the series a single file named.
struct DicomListing {
    std::vector<DicomSeries> series;
    std::size_t ignored = 0;
    std::string namedUid; ///< the series of the file `path` named ("" for a folder)
};

/// Whether `path` is read as DICOM: a folder, a file named DICOMDIR, or a
/// file with DICOM's preamble ("DICM" at byte 128) or a .dcm extension.
bool isDicomPath(const std::filesystem::path& path);

/// Lists the series under `path` (see above). Throws InputError naming `path`
/// when it holds no DICOM image.
DicomListing listDicom(const std::filesystem::path& path);

/// The series `selector` picks: its number, UID or description (exactly;
/// descriptions also ignoring case). Empty: the only series, or the series of
/// the file `path` named. Throws InputError listing the choices when none or
/// several match.
const DicomSeries& pickSeries(const DicomListing& listing, std::string_view selector,
                              const std::filesystem::path& path);

/// A series' choices, one line each: number, description, UID, grid, files.
std::string describeSeries(const DicomListing& listing);

/// Reads the series `selector` picks under `path` (pickSeries).
Volume readDicom(const std::filesystem::path& path, std::string_view selector = {});

namespace detail {

/// Told each file's name before GDCM reads it.
using DicomProgress = std::function<void(const std::string& file)>;

/// listDicom and readDicom in this process (they run these in a child
/// process, volume/child_process.hpp, so that GDCM's assertions on a damaged
/// file cannot abort cutaway): for the tests that show why.
DicomListing listDicomHere(const std::filesystem::path& path, const DicomProgress& progress = {});
Volume readDicomHere(const std::filesystem::path& path, std::string_view selector,
                     const DicomProgress& progress = {});

} // namespace detail

} // namespace cutaway
