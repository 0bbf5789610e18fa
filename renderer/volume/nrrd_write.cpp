// NRRD writer: attached header, little endian, raw or gzip. The file appears
// atomically: it is written under a temporary name in the target folder and
// renamed over the target (io/atomic_file.hpp), so a crash never leaves a
// half-written volume.
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "volume/byte_order.hpp"
#include "volume/gzip.hpp"
#include "volume/io_util.hpp"
#include "volume/volume.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace cutaway {

namespace {

std::string nrrdTypeName(VoxelType type) {
    // The NRRD spellings of the canonical names, except the two float types.
    switch (type) {
    case VoxelType::F32:
        return "float";
    case VoxelType::F64:
        return "double";
    default:
        return std::string(voxelTypeName(type));
    }
}

std::string header(const Volume& volume, bool gzip) {
    using detail::formatDouble;
    std::ostringstream out;
    out << "NRRD0004\n"
        << "# Complete NRRD file format specification at:\n"
        << "# http://teem.sourceforge.net/nrrd/format.html\n"
        << "type: " << nrrdTypeName(volume.type) << "\n"
        << "dimension: 3\n"
        << "sizes: " << volume.dims.x << ' ' << volume.dims.y << ' ' << volume.dims.z << "\n";
    if (volume.hasPhysicalPlacement()) {
        // The spec allows `space origin` only with a space; per-axis spacing then
        // goes in `space directions` (teem rejects `spacings` next to a space):
        // the direction of each index axis scaled by its spacing.
        const auto vector = [](glm::dvec3 v) {
            v += 0.0; // -0 as 0
            // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, its
            // bug 105329) of "(" + std::string once this is inlined.
            std::string text(1, '(');
            text += formatDouble(v.x);
            text += ',';
            text += formatDouble(v.y);
            text += ',';
            text += formatDouble(v.z);
            text += ')';
            return text;
        };
        if (volume.space == Space::LPS)
            out << "space: left-posterior-superior\n";
        else
            out << "space dimension: 3\n";
        out << "space directions: " << vector(volume.direction[0] * volume.spacing.x) << ' '
            << vector(volume.direction[1] * volume.spacing.y) << ' '
            << vector(volume.direction[2] * volume.spacing.z) << "\n"
            << "space origin: " << vector(volume.origin) << "\n";
    } else {
        out << "spacings: " << formatDouble(volume.spacing.x) << ' '
            << formatDouble(volume.spacing.y) << ' ' << formatDouble(volume.spacing.z) << "\n";
    }
    out << "kinds: domain domain domain\n"
        << "endian: little\n"
        << "encoding: " << (gzip ? "gzip" : "raw") << "\n";
    if (volume.slope != 1.0 || volume.inter != 0.0) {
        out << "cutaway_slope:=" << formatDouble(volume.slope) << "\n"
            << "cutaway_inter:=" << formatDouble(volume.inter) << "\n";
    }
    out << "\n";
    return out.str();
}

} // namespace

void writeNrrd(const std::filesystem::path& path, const Volume& volume, bool gzip) {
    const std::string ctx = path.string();
    const std::int64_t sizes[3] = {volume.dims.x, volume.dims.y, volume.dims.z};
    const std::size_t bytes = detail::checkedByteCount(sizes, volume.type, ctx);
    if (volume.data.size() != bytes) {
        throw InputError(ctx + ": volume has " + std::to_string(volume.data.size()) +
                         " bytes of data but its dims and type need " + std::to_string(bytes));
    }
    for (int a = 0; a < 3; ++a) {
        detail::checkSpacing(volume.spacing[a], a, ctx);
        const double length = glm::length(volume.direction[a]);
        if (!std::isfinite(length) || std::abs(length - 1.0) > 1e-6) {
            throw InputError(ctx + ": the direction of axis " + std::to_string(a) +
                             " is not a unit vector");
        }
    }
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(volume.origin[a])) throw InputError(ctx + ": the origin is not finite");
    }

    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) {
            throw RuntimeError(ctx + ": cannot write: cannot create " + temporary.string() + " (" +
                               std::strerror(errno) + ")");
        }
        const std::string text = header(volume, gzip);
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        const std::byte* voxels = volume.data.data();
        std::vector<std::byte> swapped;
        if (detail::needsSwap(false) && voxelSize(volume.type) > 1) {
            swapped = volume.data;
            detail::swapBytes(swapped.data(), volume.voxelCount(), voxelSize(volume.type));
            voxels = swapped.data();
        }
        const auto failed = [&] {
            return RuntimeError(ctx + ": cannot write: writing the data failed (disk full?)");
        };
        try {
            if (gzip) {
                detail::writeGzip(out, voxels, bytes, ctx);
            } else {
                out.write(reinterpret_cast<const char*>(voxels),
                          static_cast<std::streamsize>(bytes));
            }
        } catch (const RuntimeError&) {
            throw failed();
        }
        out.close();
        if (!out) throw failed();
    });
}

} // namespace cutaway
