// Every reader, every voxel type: files written by hand or by writeNrrd read
// back with the right shape, type, spacing and every voxel.
#include "volume_test_util.hpp"

#include <cmath>
#include <cstring>
#include <limits>

namespace cutaway::test {
namespace {

constexpr VoxelType kTypes[] = {VoxelType::U8,  VoxelType::I8,  VoxelType::U16, VoxelType::I16,
                                VoxelType::U32, VoxelType::I32, VoxelType::F32, VoxelType::F64};

template <typename T>
void fillTyped(Volume& v) {
    T* p = reinterpret_cast<T*>(v.data.data());
    const std::size_t n = v.voxelCount();
    for (std::size_t i = 0; i < n; ++i) {
        if constexpr (std::is_floating_point_v<T>)
            p[i] = static_cast<T>((static_cast<double>(i) - 20.0) * 1.75e3 + 0.125);
        else
            p[i] = static_cast<T>(std::numeric_limits<T>::min() + static_cast<T>(i * 37));
    }
    p[0] = std::numeric_limits<T>::lowest();
    p[1] = std::numeric_limits<T>::max();
}

// A 5 x 4 x 3 volume with the type's extremes and a spread of values.
Volume sample(VoxelType type, glm::dvec3 spacing = {0.5, 1.25, 3.0}) {
    Volume v = Volume::allocate({5, 4, 3}, type, spacing);
    switch (type) {
    case VoxelType::U8:
        fillTyped<std::uint8_t>(v);
        break;
    case VoxelType::I8:
        fillTyped<std::int8_t>(v);
        break;
    case VoxelType::U16:
        fillTyped<std::uint16_t>(v);
        break;
    case VoxelType::I16:
        fillTyped<std::int16_t>(v);
        break;
    case VoxelType::U32:
        fillTyped<std::uint32_t>(v);
        break;
    case VoxelType::I32:
        fillTyped<std::int32_t>(v);
        break;
    case VoxelType::F32:
        fillTyped<float>(v);
        break;
    case VoxelType::F64:
        fillTyped<double>(v);
        break;
    }
    return v;
}

void expectSame(const Volume& got, const Volume& want) {
    EXPECT_EQ(got.dims, want.dims);
    EXPECT_EQ(got.type, want.type) << voxelTypeName(got.type);
    // 1e-6: NIfTI stores pixdim as float32.
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(got.spacing[a], want.spacing[a], 1e-6) << a;
    ASSERT_EQ(got.voxelCount(), want.voxelCount());
    for (std::size_t i = 0; i < want.voxelCount(); ++i)
        ASSERT_EQ(got.raw(i), want.raw(i)) << "voxel " << i << " " << voxelTypeName(want.type);
}

int niftiCode(VoxelType t) {
    switch (t) {
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

std::string voxelBytes(const Volume& v) {
    return bytesOf(v.data.data(), v.data.size());
}

NiftiHeader niftiFor(const Volume& v) {
    NiftiHeader h;
    h.dims[1] = static_cast<std::int16_t>(v.dims.x);
    h.dims[2] = static_cast<std::int16_t>(v.dims.y);
    h.dims[3] = static_cast<std::int16_t>(v.dims.z);
    h.datatype = static_cast<std::int16_t>(niftiCode(v.type));
    h.bitpix = static_cast<std::int16_t>(8 * voxelSize(v.type));
    for (int a = 0; a < 3; ++a)
        h.pixdim[a + 1] = static_cast<float>(v.spacing[a]);
    return h;
}

} // namespace

using VolumeFormats = VolumeFiles;

TEST_F(VolumeFormats, NrrdRawAndGzipRoundTripEveryType) {
    for (VoxelType type : kTypes) {
        SCOPED_TRACE(std::string(voxelTypeName(type)));
        const Volume v = sample(type);
        for (bool gz : {false, true}) {
            const auto file = path(std::string(voxelTypeName(type)) + (gz ? "_gz" : "") + ".nrrd");
            writeNrrd(file, v, gz);
            expectSame(readVolume(file), v);
        }
    }
}

TEST_F(VolumeFormats, NrrdDetachedHeaderAndSkips) {
    const Volume v = sample(VoxelType::I16, {2.0, 2.0, 0.7});
    writeFile("data.raw", std::string(7, 'x') + voxelBytes(v)); // 7 bytes to skip
    writeFile("head.nhdr", "NRRD0004\n# a comment\ntype: short\ndimension: 3\nsizes: 5 4 3\n"
                           "spacings: 2 2 0.7\nencoding: raw\nendian: little\n"
                           "byte skip: 7\ndata file: data.raw\n");
    expectSame(readVolume(path("head.nhdr")), v);

    // byte skip -1: the data are the last bytes of the file.
    writeFile("tail.raw", std::string(100, 'y') + voxelBytes(v));
    writeFile("tail.nhdr", "NRRD0004\ntype: int16\ndimension: 3\nsizes: 5 4 3\nspacings: 2 2 0.7\n"
                           "encoding: raw\nendian: little\nbyte skip: -1\ndatafile: tail.raw\n");
    expectSame(readVolume(path("tail.nhdr")), v);
}

TEST_F(VolumeFormats, NrrdBigEndianWithSpaceDirections) {
    const Volume v = sample(VoxelType::F32, {2.0, 3.0, 0.5});
    const std::string header =
        "NRRD0005\ntype: float\ndimension: 3\nspace: left-posterior-superior\nsizes: 5 4 3\n"
        "space directions: (2,0,0) (0,-3,0) (0,0,0.5)\nspace origin: (10,20,30)\n"
        "kinds: domain domain domain\nendian: big\nencoding: gzip\n\n";
    writeFile("big.nrrd", header + gzip(byteSwapped(voxelBytes(v), 4)));
    const Volume got = readVolume(path("big.nrrd"));
    expectSame(got, v); // spacing is the length of each direction vector
    EXPECT_EQ(got.origin, glm::dvec3(10, 20, 30));
    EXPECT_EQ(got.space, Space::LPS);
    EXPECT_EQ(got.direction, glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0),
                                        glm::dvec3(0, 0, 1))); // its length is the spacing
}

TEST_F(VolumeFormats, NrrdFourDimensionsWithAUnitFirstAxis) {
    const Volume v = sample(VoxelType::U8, {1, 1, 1});
    writeFile("four.nrrd", "NRRD0004\ntype: uchar\ndimension: 4\nsizes: 1 5 4 3\n"
                           "space directions: none (1,0,0) (0,1,0) (0,0,1)\nencoding: raw\n\n" +
                               voxelBytes(v));
    expectSame(readVolume(path("four.nrrd")), v);
}

TEST_F(VolumeFormats, NiftiPlainAndGzippedEveryType) {
    for (VoxelType type : kTypes) {
        SCOPED_TRACE(std::string(voxelTypeName(type)));
        const Volume v = sample(type, {1.5, 2.0, 0.8});
        const std::string file = niftiFor(v).bytes() + voxelBytes(v);
        expectSame(readVolume(writeFile("v.nii", file)), v);
        expectSame(readVolume(writeFile("v.nii.gz", gzip(file))), v);
    }
}

TEST_F(VolumeFormats, NiftiScalingSlopeAndIntercept) {
    const Volume v = sample(VoxelType::I16, {1, 1, 1});
    NiftiHeader h = niftiFor(v);
    h.sclSlope = 0.0f; // "no scaling"
    Volume none = readVolume(writeFile("a.nii", h.bytes() + voxelBytes(v)));
    EXPECT_EQ(none.value(5), v.raw(5));
    h.sclSlope = std::nanf("");
    none = readVolume(writeFile("b.nii", h.bytes() + voxelBytes(v)));
    EXPECT_EQ(none.value(5), v.raw(5));
    h.sclSlope = 2.0f;
    h.sclInter = -10.0f;
    Volume scaled = readVolume(writeFile("c.nii", h.bytes() + voxelBytes(v)));
    for (std::size_t i = 0; i < v.voxelCount(); ++i)
        ASSERT_DOUBLE_EQ(scaled.value(i), 2.0 * v.raw(i) - 10.0) << i;
    const ValueRange r = valueRange(scaled);
    EXPECT_DOUBLE_EQ(r.min, 2.0 * -32768 - 10.0);
    EXPECT_DOUBLE_EQ(r.max, 2.0 * 32767 - 10.0);
}

TEST_F(VolumeFormats, NiftiBigEndianAndNegativePixdim) {
    const Volume v = sample(VoxelType::U16, {1.5, 2.0, 0.8});
    NiftiHeader h = niftiFor(v);
    h.pixdim[1] = -1.5f; // a flipped axis: the spacing is the magnitude
    std::string header = h.bytes();
    // Swap every multi-byte field we set to big endian.
    auto swapAt = [&](std::size_t at, std::size_t width, std::size_t count) {
        for (std::size_t k = 0; k < count; ++k)
            std::reverse(header.begin() + static_cast<std::ptrdiff_t>(at + k * width),
                         header.begin() + static_cast<std::ptrdiff_t>(at + (k + 1) * width));
    };
    swapAt(0, 4, 1);   // sizeof_hdr
    swapAt(40, 2, 8);  // dim
    swapAt(70, 2, 2);  // datatype, bitpix
    swapAt(76, 4, 8);  // pixdim
    swapAt(108, 4, 3); // vox_offset, scl_slope, scl_inter
    const Volume got = readVolume(writeFile("be.nii", header + byteSwapped(voxelBytes(v), 2)));
    expectSame(got, v);
}

// An sform that permutes and flips the axes (i runs inferior, j to the left,
// k anterior, in NIfTI's RAS) reads into LPS.
TEST_F(VolumeFormats, NiftiSformReadsIntoLps) {
    const Volume v = sample(VoxelType::U8, {2.0, 3.0, 4.0});
    NiftiHeader h = niftiFor(v);
    h.sformCode = 2;
    const float srow[3][4] = {{0, -3, 0, 10}, {0, 0, 4, -20}, {-2, 0, 0, 30}};
    std::memcpy(h.srow, srow, sizeof srow);
    h.qformCode = 1; // set too, but the sform wins
    h.quatern[2] = 1.0f;
    const Volume got = readVolume(writeFile("s.nii", h.bytes() + voxelBytes(v)));
    expectSame(got, v);
    EXPECT_EQ(got.space, Space::LPS);
    // RAS (x, y, z) is LPS (-x, -y, z).
    EXPECT_EQ(got.origin, glm::dvec3(-10, 20, 30));
    EXPECT_EQ(got.direction[0], glm::dvec3(0, 0, -1));
    EXPECT_EQ(got.direction[1], glm::dvec3(1, 0, 0));
    EXPECT_EQ(got.direction[2], glm::dvec3(0, -1, 0));
    // Voxel (4, 3, 2), by hand: RAS x = -3 * 3 + 10 = 1, y = 4 * 2 - 20 = -12,
    // z = -2 * 4 + 30 = 22; in LPS (-1, 12, 22).
    const glm::dvec3 corner = got.physicalPosition({4, 3, 2});
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(corner[a], glm::dvec3(-1, 12, 22)[a], 1e-12) << a;
}

// Without an sform, the qform: a rotation by 60 degrees about z (quaternion
// d = sin 30, a = cos 30) with qfac -1 flipping k. Neither: no orientation.
TEST_F(VolumeFormats, NiftiQformReadsIntoLpsAndNeitherIsNone) {
    const Volume v = sample(VoxelType::I16, {2.0, 3.0, 4.0});
    NiftiHeader h = niftiFor(v);
    h.qformCode = 1;
    h.quatern[2] = 0.5f;
    h.pixdim[0] = -1.0f;
    h.qoffset[0] = 5.0f;
    h.qoffset[1] = 6.0f;
    h.qoffset[2] = 7.0f;
    h.sformCode = 0;
    h.srow[0][3] = 99.0f; // unused: sform_code 0
    const Volume got = readVolume(writeFile("q.nii", h.bytes() + voxelBytes(v)));
    expectSame(got, v);
    EXPECT_EQ(got.space, Space::LPS);
    // Voxel (4, 3, 2) in RAS: (5, 6, 7) + 8 (cos 60, sin 60, 0) + 9 (-sin 60, cos 60, 0)
    // + 8 (0, 0, -1); in LPS x and y negated.
    const double c = 0.5, s = std::sqrt(3.0) / 2.0;
    const glm::dvec3 ras(5 + 8 * c - 9 * s, 6 + 8 * s + 9 * c, 7 - 8);
    const glm::dvec3 corner = got.physicalPosition({4, 3, 2});
    EXPECT_NEAR(corner.x, -ras.x, 1e-5);
    EXPECT_NEAR(corner.y, -ras.y, 1e-5);
    EXPECT_NEAR(corner.z, ras.z, 1e-5);
    EXPECT_EQ(got.origin, glm::dvec3(-5, -6, 7));

    h.qformCode = 0;
    const Volume none = readVolume(writeFile("n.nii", h.bytes() + voxelBytes(v)));
    EXPECT_EQ(none.space, Space::None);
    EXPECT_EQ(none.origin, glm::dvec3(0.0));
    EXPECT_EQ(none.direction, glm::dmat3(1.0));

    // An sform with an axis of no length is not an orientation: the qform is taken.
    h.qformCode = 1;
    h.sformCode = 1;
    const Volume degenerate = readVolume(writeFile("d.nii", h.bytes() + voxelBytes(v)));
    EXPECT_EQ(degenerate.origin, glm::dvec3(-5, -6, 7));
}

// A NRRD written from a NIfTI keeps its LPS geometry: every voxel centre in
// the same place.
TEST_F(VolumeFormats, NiftiOrientationSurvivesANrrdRoundTrip) {
    const Volume v = sample(VoxelType::U8, {2.0, 3.0, 4.0});
    NiftiHeader h = niftiFor(v);
    h.sformCode = 1;
    const float srow[3][4] = {{0, -3, 0, 10}, {0, 0, 4, -20}, {-2, 0, 0, 30}};
    std::memcpy(h.srow, srow, sizeof srow);
    const Volume nifti = readVolume(writeFile("s.nii", h.bytes() + voxelBytes(v)));
    writeNrrd(path("s.nrrd"), nifti);
    const Volume nrrd = readVolume(path("s.nrrd"));
    EXPECT_EQ(nrrd.space, Space::LPS);
    for (int z = 0; z < v.dims.z; ++z)
        for (int y = 0; y < v.dims.y; ++y)
            for (int x = 0; x < v.dims.x; ++x) {
                const glm::dvec3 a = nifti.physicalPosition({x, y, z});
                const glm::dvec3 b = nrrd.physicalPosition({x, y, z});
                ASSERT_NEAR(glm::distance(a, b), 0.0, 1e-9) << x << ' ' << y << ' ' << z;
            }
}

TEST_F(VolumeFormats, RawWithOffsetAndByteOrder) {
    const Volume v = sample(VoxelType::I32, {0.9, 0.9, 2.5});
    RawLayout layout;
    layout.dims = v.dims;
    layout.type = v.type;
    layout.spacing = v.spacing;
    layout.offset = 13;
    expectSame(readRaw(writeFile("le.raw", std::string(13, '\0') + voxelBytes(v)), layout), v);
    layout.bigEndian = true;
    expectSame(
        readRaw(writeFile("be.raw", std::string(13, '\0') + byteSwapped(voxelBytes(v), 4)), layout),
        v);
    layout.offset = 14; // one byte short now
    EXPECT_NE(inputError([&] { readRaw(path("be.raw"), layout); }).find("be.raw"),
              std::string::npos);
}

TEST_F(VolumeFormats, WriteNrrdLeavesNoTemporaryAndReplacesAtomically) {
    const Volume v = sample(VoxelType::U8);
    writeNrrd(path("a.nrrd"), v, true);
    writeNrrd(path("a.nrrd"), sample(VoxelType::I16), false);
    EXPECT_EQ(readVolume(path("a.nrrd")).type, VoxelType::I16);
    int entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(m_dir))
        ++entries;
    EXPECT_EQ(entries, 1);
    EXPECT_THROW(writeNrrd(path("missing-folder/a.nrrd"), v), RuntimeError);
}

TEST(VoxelTypes, NamesRoundTripAndSizesAreRight) {
    for (VoxelType t : kTypes)
        EXPECT_EQ(parseVoxelType(voxelTypeName(t), "test"), t);
    EXPECT_EQ(voxelSize(VoxelType::I16), 2u);
    EXPECT_EQ(voxelSize(VoxelType::F64), 8u);
    EXPECT_THROW(parseVoxelType("complex", "test"), InputError);
}

} // namespace cutaway::test
