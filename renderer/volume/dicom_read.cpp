// Reading one DICOM series into a volume: each file decoded by GDCM's
// ImageReader (whatever transfer syntax Debian's GDCM decodes), the slices
// checked to form one regular grid and stacked along their normal.
#include "core/error.hpp"
#include "core/quote_text.hpp"
#include "volume/dicom.hpp"
#include "volume/io_util.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <gdcmDataSet.h>
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmPixelFormat.h>
#include <gdcmReader.h>
#include <optional>

namespace cutaway {
namespace {

namespace fs = std::filesystem;

struct Slice {
    std::string file;
    glm::ivec2 dims{0};
    VoxelType type = VoxelType::U8;
    glm::dvec3 position{0.0}; // ImagePositionPatient: the first voxel's centre, LPS mm
    glm::dvec3 row{1, 0, 0}, column{0, 1, 0};
    glm::dvec2 spacing{1.0}; // along a row (x), along a column (y)
    double thickness = 1.0;  // GDCM's third spacing: for a series of one slice
    double slope = 1.0, inter = 0.0;
    std::vector<std::byte> pixels;
    double along = 0.0; // position along the stack's normal
};

std::optional<VoxelType> voxelTypeOf(const gdcm::PixelFormat& pf) {
    switch (pf.GetScalarType()) {
    case gdcm::PixelFormat::UINT8:
        return VoxelType::U8;
    case gdcm::PixelFormat::INT8:
        return VoxelType::I8;
    case gdcm::PixelFormat::UINT16:
        return VoxelType::U16;
    case gdcm::PixelFormat::INT16:
        return VoxelType::I16;
    case gdcm::PixelFormat::UINT32:
        return VoxelType::U32;
    case gdcm::PixelFormat::INT32:
        return VoxelType::I32;
    case gdcm::PixelFormat::FLOAT32:
        return VoxelType::F32;
    case gdcm::PixelFormat::FLOAT64:
        return VoxelType::F64;
    default:
        return std::nullopt;
    }
}

const gdcm::Tag kPixelData(0x7fe0, 0x0010);
const gdcm::Tag kPixelSpacing(0x0028, 0x0030);

// An element's bytes as text ("" when absent or not a plain value).
std::string elementText(const gdcm::DataSet& ds, const gdcm::Tag& tag) {
    if (!ds.FindDataElement(tag)) return {};
    const gdcm::ByteValue* bv = ds.GetDataElement(tag).GetByteValue();
    return bv ? std::string(bv->GetPointer(), bv->GetLength()) : std::string();
}

// PixelSpacing as written, read here rather than through GDCM (which reads
// uninitialised memory on "nan"): two finite numbers > 0, or refused. Empty
// when the file has none (GDCM's spacing then stands).
std::optional<glm::dvec2> pixelSpacing(const gdcm::DataSet& ds, const std::string& file) {
    std::string text = elementText(ds, kPixelSpacing);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\0'))
        text.pop_back();
    if (text.empty()) return std::nullopt;
    const std::size_t bar = text.find('\\');
    double row = 0.0, column = 0.0;
    const bool parsed =
        bar != std::string::npos &&
        detail::parseDouble(detail::trim(std::string_view(text).substr(0, bar)), row) &&
        detail::parseDouble(detail::trim(std::string_view(text).substr(bar + 1)), column);
    if (!parsed || !std::isfinite(row) || !std::isfinite(column) || row <= 0.0 || column <= 0.0)
        throw InputError(file + ": PixelSpacing " + quoteText(text, 64) +
                         " is not two finite spacings > 0 (mm between rows, between columns)");
    return glm::dvec2(column, row); // along a row (x) is the spacing between columns
}

// The bytes from where the file's pixel data begins to its end: GDCM keeps
// the declared length of pixel data cut short, its missing end zeros.
std::uint64_t pixelBytesInFile(const std::string& file) {
    gdcm::Reader reader;
    reader.SetFileName(file.c_str());
    if (!reader.ReadUpToTag(kPixelData, {kPixelData})) return 0; // stops at its value
    std::error_code ec;
    const std::uint64_t size = fs::file_size(file, ec);
    const std::uint64_t start = reader.GetStreamCurrentPosition();
    return ec || start > size ? 0 : size - start;
}

// Refuses pixel data shorter than the image's rows and columns need, as
// declared or as the file holds it: GDCM pads both with zeros. (Compressed
// pixel data is checked by its decoder.)
void checkPixelDataLength(const gdcm::DataSet& ds, std::size_t expected, const Slice& s) {
    if (!ds.FindDataElement(kPixelData)) throw InputError(s.file + ": no pixel data");
    const gdcm::ByteValue* bv = ds.GetDataElement(kPixelData).GetByteValue();
    if (!bv) return;
    const std::uint64_t held = std::min<std::uint64_t>(bv->GetLength(), pixelBytesInFile(s.file));
    if (held >= expected) return;
    throw InputError(s.file + ": its pixel data holds " + std::to_string(held) + " bytes where " +
                     std::to_string(s.dims.x) + " x " + std::to_string(s.dims.y) + " pixels need " +
                     std::to_string(expected) +
                     " (cut short, or Rows and Columns say more than it holds)");
}

// The series' memory, from its first file's header, refused before any
// slice is read when it is more than a volume may hold.
void checkSeriesSize(const DicomSeries& series, const fs::path& path) {
    const std::int64_t sizes[3] = {series.dims.x, series.dims.y, series.dims.z};
    const int bytes = std::max(1, (series.bitsAllocated + 7) / 8);
    const VoxelType like = bytes <= 1   ? VoxelType::U8
                           : bytes == 2 ? VoxelType::U16
                           : bytes <= 4 ? VoxelType::U32
                                        : VoxelType::F64;
    detail::checkedByteCount(sizes, like, path.string() + " (series " + series.uid + ")");
}

Slice readSlice(const std::string& file, const DicomSeries& series) {
    gdcm::ImageReader reader;
    reader.SetFileName(file.c_str());
    if (!reader.Read()) throw InputError(file + ": GDCM cannot read it as a DICOM image");
    const gdcm::Image& image = reader.GetImage();
    if (image.GetNumberOfDimensions() != 2 && image.GetDimension(2) > 1)
        throw InputError(file + ": a multi-frame image (" + std::to_string(image.GetDimension(2)) +
                         " frames); only series of single-frame images are read");
    const gdcm::PixelFormat& pf = image.GetPixelFormat();
    const std::optional<VoxelType> type = voxelTypeOf(pf);
    if (pf.GetSamplesPerPixel() != 1 || !type)
        throw InputError(file + ": pixels of " + std::to_string(pf.GetSamplesPerPixel()) +
                         " sample(s) of " + pf.GetScalarTypeAsString() +
                         "; only greyscale images of integers or floats are read");
    Slice s;
    s.file = file;
    s.dims = {int(image.GetDimension(0)), int(image.GetDimension(1))};
    if (s.dims != glm::ivec2(series.dims))
        throw InputError(file + ": " + std::to_string(s.dims.x) + " x " + std::to_string(s.dims.y) +
                         " pixels, where its series' first file has " +
                         std::to_string(series.dims.x) + " x " + std::to_string(series.dims.y));
    s.type = *type;
    const double* o = image.GetOrigin();
    const double* d = image.GetDirectionCosines();
    const double* sp = image.GetSpacing();
    s.position = {o[0], o[1], o[2]};
    s.row = {d[0], d[1], d[2]};
    s.column = {d[3], d[4], d[5]};
    s.spacing = {sp[0], sp[1]};
    const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
    if (const auto written = pixelSpacing(ds, file)) s.spacing = *written;
    s.thickness = sp[2] > 0.0 ? sp[2] : 1.0;
    s.slope = image.GetSlope();
    s.inter = image.GetIntercept();
    const std::size_t expected = std::size_t(s.dims.x) * s.dims.y * voxelSize(s.type);
    checkPixelDataLength(ds, expected, s);
    if (image.GetBufferLength() != expected)
        throw InputError(file + ": its pixel data holds " +
                         std::to_string(image.GetBufferLength()) + " bytes where " +
                         std::to_string(s.dims.x) + " x " + std::to_string(s.dims.y) +
                         " pixels need " + std::to_string(expected));
    s.pixels.resize(expected);
    if (!image.GetBuffer(reinterpret_cast<char*>(s.pixels.data())))
        throw InputError(file + ": GDCM cannot decode its pixel data (truncated, or a transfer "
                                "syntax it does not decode)");
    return s;
}

// Every slice like the first in size, type, orientation and pixel spacing.
void checkAlike(const std::vector<Slice>& slices) {
    const Slice& a = slices.front();
    for (const Slice& b : slices) {
        const auto differs = [&](const std::string& what) {
            throw InputError(b.file + ": its " + what + " differs from " + a.file +
                             "'s; the series' slices must form one grid");
        };
        if (b.dims != a.dims) differs("size");
        if (b.type != a.type) differs("pixel type");
        if (glm::length(b.row - a.row) > 1e-4 || glm::length(b.column - a.column) > 1e-4)
            differs("orientation (ImageOrientationPatient)");
        if (glm::any(glm::greaterThan(glm::abs(b.spacing - a.spacing), 1e-4 * a.spacing)))
            differs("pixel spacing");
    }
    for (int axis = 0; axis < 2; ++axis)
        detail::checkSpacing(a.spacing[axis], axis, a.file);
}

std::string mm(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g mm", v);
    return text;
}

// Sorts the slices along their normal and returns the spacing between them,
// refusing a stack that is not one regular grid.
double stack(std::vector<Slice>& slices, glm::dvec3 normal) {
    for (Slice& s : slices)
        s.along = glm::dot(s.position, normal);
    std::sort(slices.begin(), slices.end(),
              [](const Slice& a, const Slice& b) { return a.along < b.along; });
    if (slices.size() == 1) return slices.front().thickness;
    std::vector<double> gaps;
    for (std::size_t k = 1; k < slices.size(); ++k)
        gaps.push_back(slices[k].along - slices[k - 1].along);
    std::vector<double> sorted = gaps;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double spacing = sorted[sorted.size() / 2];
    const double tolerance = std::max(0.01, 0.01 * spacing);
    for (std::size_t k = 0; k < gaps.size(); ++k) {
        const Slice &a = slices[k], &b = slices[k + 1];
        if (gaps[k] < 1e-3)
            throw InputError(a.file + " and " + b.file + ": two slices at one position (" +
                             mm(a.along) + " along the normal)");
        if (std::abs(gaps[k] - spacing) <= tolerance) continue;
        const double steps = std::round(gaps[k] / spacing);
        if (steps >= 2 && std::abs(gaps[k] - steps * spacing) <= steps * tolerance)
            throw InputError("slices missing between " + a.file + " and " + b.file + ": " +
                             mm(gaps[k]) + " apart where the series' slices are " + mm(spacing) +
                             " apart");
        throw InputError("uneven slice spacing: " + a.file + " and " + b.file + " are " +
                         mm(gaps[k]) + " apart where the series' slices are " + mm(spacing) +
                         " apart");
    }
    for (const Slice& s : slices) {
        const glm::dvec3 offset = s.position - slices.front().position;
        const double off = glm::length(offset - glm::dot(offset, normal) * normal);
        if (off > tolerance)
            throw InputError(s.file + ": lies " + mm(off) + " off the stack's normal from " +
                             slices.front().file +
                             " (a gantry tilt or a sheared stack); resample the series "
                             "to an orthogonal grid first");
    }
    detail::checkSpacing(spacing, 2, slices.front().file);
    return spacing;
}

// The slices' voxels in one volume; rescaled to float32 when their slopes or
// intercepts differ.
void fill(Volume& v, std::vector<Slice>& slices) {
    const bool shared = std::all_of(slices.begin(), slices.end(), [&](const Slice& s) {
        return s.slope == slices.front().slope && s.inter == slices.front().inter;
    });
    const VoxelType stored = slices.front().type;
    v.type = shared ? stored : VoxelType::F32;
    v.slope = shared ? slices.front().slope : 1.0;
    v.inter = shared ? slices.front().inter : 0.0;
    const std::size_t perSlice = std::size_t(v.dims.x) * v.dims.y;
    v.data.resize(perSlice * slices.size() * voxelSize(v.type));
    for (std::size_t z = 0; z < slices.size(); ++z) {
        Slice& s = slices[z];
        std::byte* dst = v.data.data() + z * perSlice * voxelSize(v.type);
        if (shared) {
            std::memcpy(dst, s.pixels.data(), s.pixels.size());
        } else {
            Volume one = Volume::allocate(glm::ivec3(v.dims.x, v.dims.y, 1), stored);
            one.data = std::move(s.pixels);
            for (std::size_t i = 0; i < perSlice; ++i) {
                const float value = float(one.raw(i) * s.slope + s.inter);
                std::memcpy(dst + i * sizeof value, &value, sizeof value);
            }
        }
        std::vector<std::byte>().swap(s.pixels);
    }
}

} // namespace

namespace detail {

Volume readDicomHere(const fs::path& path, std::string_view selector,
                     const DicomProgress& progress) {
    const DicomListing listing = listDicomHere(path, progress);
    const DicomSeries& series = pickSeries(listing, selector, path);
    checkSeriesSize(series, path);
    std::vector<Slice> slices;
    for (const fs::path& file : series.files) {
        if (progress) progress(file.string());
        slices.push_back(readSlice(file.string(), series));
    }
    checkAlike(slices);
    const Slice& first = slices.front();
    const glm::dvec3 normal = glm::normalize(glm::cross(first.row, first.column));
    const double between = stack(slices, normal);
    const std::int64_t sizes[3] = {first.dims.x, first.dims.y, std::int64_t(slices.size())};
    detail::checkedByteCount(sizes, first.type, path.string());
    Volume v;
    v.dims = glm::ivec3(first.dims, int(slices.size()));
    v.spacing = glm::dvec3(first.spacing, between);
    v.origin = slices.front().position;
    v.direction = glm::dmat3(first.row, first.column, normal);
    v.space = Space::LPS;
    fill(v, slices);
    return v;
}

} // namespace detail

} // namespace cutaway
