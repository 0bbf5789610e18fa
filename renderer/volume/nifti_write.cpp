// NIfTI-1 writer (.nii, or .nii.gz gzip-compressed): a single-file header of
// 348 bytes, an empty extension flag, then the voxels, little endian. A
// volume in patient coordinates (Space::LPS) gets its affine in RAS as both
// the sform (exact) and the qform (its rotation, for readers that take only
// that; a sheared grid's is approximate), with the codes the volume's own
// NIfTI gave (Volume::niftiCodes), else 1 (scanner); any other, a
// space without anatomical meaning too, gets the spacing alone (codes 0). Written atomically, as
// the NRRD writer does.
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "volume/byte_order.hpp"
#include "volume/gzip.hpp"
#include "volume/io_util.hpp"
#include "volume/volume.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace cutaway {

namespace {

constexpr std::size_t kHeaderSize = 348;
constexpr std::size_t kVoxOffset = 352; // the header and 4 bytes of extension flag

std::int16_t niftiCode(VoxelType type) {
    switch (type) {
    case VoxelType::U8:
        return 2;
    case VoxelType::I16:
        return 4;
    case VoxelType::I32:
        return 8;
    case VoxelType::F32:
        return 16;
    case VoxelType::F64:
        return 64;
    case VoxelType::I8:
        return 256;
    case VoxelType::U16:
        return 512;
    case VoxelType::U32:
        return 768;
    }
    return 0;
}

class Header {
public:
    template <typename T>
    void put(std::size_t offset, T value) {
        std::memcpy(m_bytes.data() + offset, &value, sizeof value);
        if (detail::needsSwap(false)) detail::swapBytes(m_bytes.data() + offset, 1, sizeof value);
    }
    const std::array<std::byte, kVoxOffset>& bytes() const { return m_bytes; }
    void text(std::size_t offset, const char* s) {
        std::memcpy(m_bytes.data() + offset, s, std::strlen(s));
    }

private:
    std::array<std::byte, kVoxOffset> m_bytes{};
};

// The qform's quaternion (b, c, d) and qfac of the rotation part of `r`
// (unit columns; a mirror goes into qfac), as the NIfTI reference code
// derives it from the largest of the four candidate terms.
std::array<double, 4> quaternionOf(glm::dmat3 r) {
    double qfac = 1.0;
    if (glm::determinant(r) < 0.0) {
        r[2] = -r[2];
        qfac = -1.0;
    }
    // r[c][row] is column c: R(row, col) = r[col][row].
    const auto R = [&](int row, int col) { return r[col][row]; };
    double a = R(0, 0) + R(1, 1) + R(2, 2) + 1.0, b, c, d;
    if (a > 0.5) {
        a = 0.5 * std::sqrt(a);
        b = 0.25 * (R(2, 1) - R(1, 2)) / a;
        c = 0.25 * (R(0, 2) - R(2, 0)) / a;
        d = 0.25 * (R(1, 0) - R(0, 1)) / a;
    } else {
        const double xd = 1.0 + R(0, 0) - (R(1, 1) + R(2, 2));
        const double yd = 1.0 + R(1, 1) - (R(0, 0) + R(2, 2));
        const double zd = 1.0 + R(2, 2) - (R(0, 0) + R(1, 1));
        if (xd > 1.0) {
            b = 0.5 * std::sqrt(xd);
            c = 0.25 * (R(0, 1) + R(1, 0)) / b;
            d = 0.25 * (R(0, 2) + R(2, 0)) / b;
            a = 0.25 * (R(2, 1) - R(1, 2)) / b;
        } else if (yd > 1.0) {
            c = 0.5 * std::sqrt(yd);
            b = 0.25 * (R(0, 1) + R(1, 0)) / c;
            d = 0.25 * (R(1, 2) + R(2, 1)) / c;
            a = 0.25 * (R(0, 2) - R(2, 0)) / c;
        } else {
            d = 0.5 * std::sqrt(zd);
            b = 0.25 * (R(0, 2) + R(2, 0)) / d;
            c = 0.25 * (R(1, 2) + R(2, 1)) / d;
            a = 0.25 * (R(1, 0) - R(0, 1)) / d;
        }
        if (a < 0.0) {
            b = -b;
            c = -c;
            d = -d;
        }
    }
    return {b, c, d, qfac};
}

Header headerOf(const Volume& v) {
    Header h;
    h.put<std::int32_t>(0, kHeaderSize);
    const std::int16_t dim[8] = {
        3, std::int16_t(v.dims.x), std::int16_t(v.dims.y), std::int16_t(v.dims.z), 1, 1, 1, 1};
    for (int i = 0; i < 8; ++i)
        h.put<std::int16_t>(40 + 2 * std::size_t(i), dim[i]);
    h.put<std::int16_t>(70, niftiCode(v.type));
    h.put<std::int16_t>(72, std::int16_t(8 * voxelSize(v.type)));
    h.put<float>(108, float(kVoxOffset));
    h.put<float>(112, float(v.slope));
    h.put<float>(116, float(v.inter));
    h.put<std::uint8_t>(123, 2); // xyzt_units: millimetres
    h.text(148, "cutaway export");
    double qfac = 1.0;
    if (v.space == Space::LPS) {
        // LPS to NIfTI's RAS: x and y negated.
        const glm::dmat3 flip(-1, 0, 0, 0, -1, 0, 0, 0, 1);
        const glm::dmat3 rotation = flip * v.direction;
        const glm::dvec3 origin = flip * v.origin;
        const std::array<double, 4> q = quaternionOf(rotation);
        qfac = q[3];
        // The codes the scan's NIfTI gave (2 aligned, 4 MNI, ...), else 1 (scanner).
        const std::array<int, 2> codes = v.niftiCodes.value_or(std::array<int, 2>{1, 1});
        h.put<std::int16_t>(252, std::int16_t(codes[0]));
        h.put<std::int16_t>(254, std::int16_t(codes[1]));
        for (int i = 0; i < 3; ++i) {
            h.put<float>(256 + 4 * std::size_t(i), float(q[std::size_t(i)]));
            h.put<float>(268 + 4 * std::size_t(i), float(origin[i]));
            for (int c = 0; c < 3; ++c)
                h.put<float>(280 + 16 * std::size_t(i) + 4 * std::size_t(c),
                             float(rotation[c][i] * v.spacing[c]));
            h.put<float>(280 + 16 * std::size_t(i) + 12, float(origin[i]));
        }
    }
    const float pixdim[4] = {float(qfac), float(v.spacing.x), float(v.spacing.y),
                             float(v.spacing.z)};
    for (int i = 0; i < 4; ++i)
        h.put<float>(76 + 4 * std::size_t(i), pixdim[i]);
    h.text(344, "n+1");
    return h;
}

void checkWritable(const Volume& v, const std::string& ctx) {
    const std::int64_t sizes[3] = {v.dims.x, v.dims.y, v.dims.z};
    const std::size_t bytes = detail::checkedByteCount(sizes, v.type, ctx);
    if (v.data.size() != bytes)
        throw InputError(ctx + ": volume has " + std::to_string(v.data.size()) +
                         " bytes of data but its dims and type need " + std::to_string(bytes));
    for (int a = 0; a < 3; ++a)
        if (v.dims[a] > 32767)
            throw InputError(ctx + ": NIfTI-1 holds at most 32767 voxels an axis; axis " +
                             std::to_string(a) + " has " + std::to_string(v.dims[a]) +
                             ": write NRRD");
}

} // namespace

void writeNifti(const std::filesystem::path& path, const Volume& volume) {
    const std::string ctx = path.string();
    checkWritable(volume, ctx);
    const bool gzip = detail::toLower(path.filename().string()).ends_with(".gz");
    const Header header = headerOf(volume);
    std::vector<std::byte> bytes(kVoxOffset + volume.data.size());
    std::memcpy(bytes.data(), header.bytes().data(), kVoxOffset);
    if (!volume.data.empty())
        std::memcpy(bytes.data() + kVoxOffset, volume.data.data(), volume.data.size());
    if (detail::needsSwap(false) && voxelSize(volume.type) > 1)
        detail::swapBytes(bytes.data() + kVoxOffset, volume.voxelCount(), voxelSize(volume.type));
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out)
            throw RuntimeError(ctx + ": cannot write: cannot create " + temporary.string() + " (" +
                               std::strerror(errno) + ")");
        const auto failed = [&] {
            return RuntimeError(ctx + ": cannot write: writing the data failed (disk full?)");
        };
        try {
            if (gzip)
                detail::writeGzip(out, bytes.data(), bytes.size(), ctx);
            else
                out.write(reinterpret_cast<const char*>(bytes.data()),
                          static_cast<std::streamsize>(bytes.size()));
        } catch (const RuntimeError&) {
            throw failed();
        }
        out.close();
        if (!out) throw failed();
    });
}

} // namespace cutaway
