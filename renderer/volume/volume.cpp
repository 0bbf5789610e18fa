#include "volume/volume.hpp"

#include "core/error.hpp"
#include "io/input_file.hpp"
#include "volume/dicom.hpp"
#include "volume/io_util.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

namespace cutaway {

std::size_t voxelSize(VoxelType type) {
    switch (type) {
    case VoxelType::U8:
    case VoxelType::I8:
        return 1;
    case VoxelType::U16:
    case VoxelType::I16:
        return 2;
    case VoxelType::U32:
    case VoxelType::I32:
    case VoxelType::F32:
        return 4;
    case VoxelType::F64:
        return 8;
    }
    return 1; // unreachable for a valid enumerator
}

std::string_view voxelTypeName(VoxelType type) {
    switch (type) {
    case VoxelType::U8:
        return "uint8";
    case VoxelType::I8:
        return "int8";
    case VoxelType::U16:
        return "uint16";
    case VoxelType::I16:
        return "int16";
    case VoxelType::U32:
        return "uint32";
    case VoxelType::I32:
        return "int32";
    case VoxelType::F32:
        return "float32";
    case VoxelType::F64:
        return "float64";
    }
    return "unknown";
}

VoxelType parseVoxelType(std::string_view name, std::string_view context) {
    static constexpr VoxelType kAll[] = {VoxelType::U8,  VoxelType::I8,  VoxelType::U16,
                                         VoxelType::I16, VoxelType::U32, VoxelType::I32,
                                         VoxelType::F32, VoxelType::F64};
    for (VoxelType type : kAll) {
        if (voxelTypeName(type) == name) return type;
    }
    throw InputError(std::string(context) + ": unknown voxel type '" + std::string(name) +
                     "' (expected uint8, int8, uint16, int16, uint32, int32, float32 or float64)");
}

std::size_t Volume::voxelCount() const {
    if (dims.x < 1 || dims.y < 1 || dims.z < 1) return 0;
    return static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y) *
           static_cast<std::size_t>(dims.z);
}

std::size_t Volume::index(int x, int y, int z) const {
    return static_cast<std::size_t>(x) +
           static_cast<std::size_t>(dims.x) *
               (static_cast<std::size_t>(y) +
                static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(z));
}

namespace {

template <typename T>
T load(const std::byte* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));
    return value;
}

/// Calls f(T{}) with the C++ type of a voxel type.
template <typename F>
decltype(auto) withType(VoxelType type, F&& f) {
    switch (type) {
    case VoxelType::U8:
        return f(std::uint8_t{});
    case VoxelType::I8:
        return f(std::int8_t{});
    case VoxelType::U16:
        return f(std::uint16_t{});
    case VoxelType::I16:
        return f(std::int16_t{});
    case VoxelType::U32:
        return f(std::uint32_t{});
    case VoxelType::I32:
        return f(std::int32_t{});
    case VoxelType::F32:
        return f(float{});
    case VoxelType::F64:
        return f(double{});
    }
    return f(std::uint8_t{});
}

} // namespace

double Volume::raw(std::size_t i) const {
    const std::byte* p = data.data() + i * voxelSize(type);
    return withType(type, [p](auto tag) { return static_cast<double>(load<decltype(tag)>(p)); });
}

void Volume::setRaw(std::size_t i, double value) {
    std::byte* p = data.data() + i * voxelSize(type);
    withType(type, [&](auto tag) {
        const auto v = static_cast<decltype(tag)>(value);
        std::memcpy(p, &v, sizeof v);
    });
}

std::pair<double, double> storedRange(VoxelType type) {
    return withType(type, [](auto tag) {
        using T = decltype(tag);
        return std::pair<double, double>(std::numeric_limits<T>::lowest(),
                                         std::numeric_limits<T>::max());
    });
}

Volume Volume::allocate(glm::ivec3 dims, VoxelType type, glm::dvec3 spacing) {
    const std::int64_t sizes[3] = {dims.x, dims.y, dims.z};
    const std::size_t bytes = detail::checkedByteCount(sizes, type, "volume");
    for (int a = 0; a < 3; ++a)
        detail::checkSpacing(spacing[a], a, "volume");
    Volume volume;
    volume.dims = dims;
    volume.spacing = spacing;
    volume.type = type;
    volume.data.assign(bytes, std::byte{0});
    return volume;
}

ValueRange valueRange(const Volume& volume) {
    const std::size_t count =
        std::min(volume.voxelCount(), volume.data.size() / voxelSize(volume.type));
    return withType(volume.type, [&](auto tag) {
        using T = decltype(tag);
        double lo = std::numeric_limits<double>::infinity();
        double hi = -lo;
        const std::byte* p = volume.data.data();
        for (std::size_t i = 0; i < count; ++i) {
            const auto v = static_cast<double>(load<T>(p + i * sizeof(T)));
            if (!std::isfinite(v)) continue;
            if (v < lo) lo = v;
            if (v > hi) hi = v;
        }
        if (lo > hi) return ValueRange{}; // empty, or nothing finite
        double a = lo * volume.slope + volume.inter;
        double b = hi * volume.slope + volume.inter;
        if (a > b) std::swap(a, b); // a negative slope flips the order
        return ValueRange{a, b};
    });
}

namespace {

/// Counts the voxels of type T that are NaN or infinite, writing `with`
/// over each when given.
template <typename T>
std::size_t nonFiniteIn(std::byte* data, std::size_t count, std::optional<T> with) {
    std::size_t found = 0;
    for (std::size_t i = 0; i < count; ++i) {
        T value;
        std::memcpy(&value, data + i * sizeof(T), sizeof(T));
        if (std::isfinite(value)) continue;
        ++found;
        if (with) std::memcpy(data + i * sizeof(T), &*with, sizeof(T));
    }
    return found;
}

std::size_t nonFinite(Volume& volume, std::optional<double> with) {
    const std::size_t count =
        std::min(volume.voxelCount(), volume.data.size() / voxelSize(volume.type));
    if (volume.type == VoxelType::F32) {
        const auto raw = with ? std::optional<float>(static_cast<float>(*with)) : std::nullopt;
        return nonFiniteIn<float>(volume.data.data(), count, raw);
    }
    if (volume.type == VoxelType::F64) return nonFiniteIn<double>(volume.data.data(), count, with);
    return 0; // integers are always finite
}

} // namespace

std::size_t nonFiniteCount(const Volume& volume) {
    return nonFinite(const_cast<Volume&>(volume), std::nullopt); // nothing is written
}

std::size_t replaceNonFinite(Volume& volume, double value) {
    return nonFinite(volume, (value - volume.inter) / volume.slope);
}

namespace {

bool endsWith(const std::string& text, std::string_view suffix) {
    return text.size() >= suffix.size() &&
           text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

} // namespace

Volume readVolume(const std::filesystem::path& path) {
    const std::string name = detail::toLower(path.filename().string());
    const bool named = endsWith(name, ".nrrd") || endsWith(name, ".nhdr") ||
                       endsWith(name, ".nii") || endsWith(name, ".nii.gz") ||
                       endsWith(name, ".mha") || endsWith(name, ".mhd");
    if (!named && isDicomPath(path)) return readDicom(path);
    (void)InputFile(path, "volume"); // "no such file" before any talk of extensions
    if (endsWith(name, ".nrrd") || endsWith(name, ".nhdr")) return readNrrd(path);
    if (endsWith(name, ".nii") || endsWith(name, ".nii.gz")) return readNifti(path);
    if (endsWith(name, ".mha") || endsWith(name, ".mhd")) return readMetaImage(path);
    throw InputError(
        path.string() + ": unsupported file extension '" + path.extension().string() +
        "' (supported: .nrrd, .nhdr, .nii, .nii.gz, .mha, .mhd, DICOM files and folders; "
        "headerless "
        "raw files need an explicit layout)");
}

std::vector<std::filesystem::path> volumeFiles(const std::filesystem::path& path) {
    std::vector<std::filesystem::path> files{path};
    const std::string name = detail::toLower(path.filename().string());
    std::optional<std::filesystem::path> data;
    if (endsWith(name, ".nrrd") || endsWith(name, ".nhdr")) {
        data = nrrdDataFile(path);
    } else if (endsWith(name, ".mha") || endsWith(name, ".mhd")) {
        data = metaImageDataFile(path);
    } else if (isDicomPath(path)) {
        try {
            for (const DicomSeries& series : listDicom(path).series)
                files.insert(files.end(), series.files.begin(), series.files.end());
        } catch (const InputError&) {
            // Reading the volume says what is wrong with it.
        }
    }
    if (data) files.push_back(*data);
    return files;
}

} // namespace cutaway
