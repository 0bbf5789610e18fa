// Volume itself (indexing, typed access, value ranges) and NIfTI header
// details the round trips do not reach: pixdim 0, a unit 4th dimension,
// the origin, and where the data would start.
#include "volume_test_util.hpp"

#include <cmath>

namespace cutaway::test {

TEST(VolumeBasics, IndexRawAndValue) {
    Volume v = Volume::allocate({3, 4, 5}, VoxelType::I16, {1, 2, 3});
    EXPECT_EQ(v.voxelCount(), 60u);
    EXPECT_EQ(v.data.size(), 120u);
    EXPECT_EQ(v.index(2, 3, 4), 2u + 3u * (3u + 4u * 4u));
    EXPECT_EQ(v.extent(), glm::dvec3(3, 8, 15));
    reinterpret_cast<std::int16_t*>(v.data.data())[v.index(1, 2, 3)] = -7;
    v.slope = 3.0;
    v.inter = 1.0;
    EXPECT_EQ(v.raw(v.index(1, 2, 3)), -7.0);
    EXPECT_EQ(v.value(1, 2, 3), -20.0);
    EXPECT_EQ(v.value(0, 0, 0), 1.0) << "allocate zeroes the voxels";
    EXPECT_THROW(Volume::allocate({0, 4, 5}, VoxelType::U8), InputError);
    EXPECT_THROW(Volume::allocate({4, 4, 4}, VoxelType::U8, {1, NAN, 1}), InputError);
}

TEST(VolumeBasics, ValueRangeSkipsNanAndFollowsScaling) {
    Volume v = Volume::allocate({4, 1, 1}, VoxelType::F32);
    auto* f = reinterpret_cast<float*>(v.data.data());
    f[0] = NAN;
    f[1] = -2.5f;
    f[2] = 7.0f;
    f[3] = NAN;
    ValueRange r = valueRange(v);
    EXPECT_EQ(r.min, -2.5);
    EXPECT_EQ(r.max, 7.0);
    v.slope = -2.0; // a negative slope swaps the ends
    v.inter = 1.0;
    r = valueRange(v);
    EXPECT_EQ(r.min, -13.0);
    EXPECT_EQ(r.max, 6.0);
    f[1] = f[2] = NAN;
    r = valueRange(v);
    EXPECT_EQ(r.min, 0.0);
    EXPECT_EQ(r.max, 0.0);

    Volume u = Volume::allocate({2, 1, 1}, VoxelType::U32);
    reinterpret_cast<std::uint32_t*>(u.data.data())[1] = 4000000000u;
    EXPECT_EQ(valueRange(u).max, 4e9) << "unsigned 32-bit values above 2^31";
}

TEST(VolumeBasics, InfiniteVoxelsAreLeftOutOfTheRangeAndCanBeReplaced) {
    Volume v = Volume::allocate({5, 1, 1}, VoxelType::F64);
    auto* d = reinterpret_cast<double*>(v.data.data());
    d[0] = INFINITY;
    d[1] = -1.5;
    d[2] = 3.0;
    d[3] = -INFINITY;
    d[4] = NAN;
    EXPECT_EQ(valueRange(v).min, -1.5); // was -inf
    EXPECT_EQ(valueRange(v).max, 3.0);  // was inf: the window [min, inf] blanked the image
    EXPECT_EQ(nonFiniteCount(v), 3u);
    v.slope = 2.0;
    v.inter = 1.0;
    EXPECT_EQ(replaceNonFinite(v, -2.0), 3u); // the physical value -2: raw -1.5
    EXPECT_EQ(nonFiniteCount(v), 0u);
    EXPECT_EQ(v.value(0), -2.0);
    EXPECT_EQ(v.value(3), -2.0);
    EXPECT_EQ(v.value(4), -2.0);
    EXPECT_EQ(v.value(2), 7.0) << "finite voxels stay";
    Volume f = Volume::allocate({2, 1, 1}, VoxelType::F32);
    reinterpret_cast<float*>(f.data.data())[1] = -INFINITY;
    EXPECT_EQ(nonFiniteCount(f), 1u);
    EXPECT_EQ(replaceNonFinite(f, 0.0), 1u);
    EXPECT_EQ(f.value(1), 0.0);
    // Integers are always finite.
    Volume u = Volume::allocate({2, 1, 1}, VoxelType::U16);
    EXPECT_EQ(nonFiniteCount(u), 0u);
    EXPECT_EQ(replaceNonFinite(u, 5.0), 0u);
    EXPECT_EQ(u.value(0), 0.0);
}

using NiftiDetails = VolumeFiles;

TEST_F(NiftiDetails, PixdimZeroIsOneMillimetreAndUnitFourthDimension) {
    NiftiHeader h;
    h.dims[0] = 4;
    h.dims[1] = 2;
    h.dims[2] = 3;
    h.dims[3] = 1;
    h.dims[4] = 1;
    h.pixdim[1] = 0.0f; // many tools write 0 when they do not know
    h.pixdim[2] = 0.75f;
    h.pixdim[3] = -2.0f;
    const Volume v = readVolume(writeFile("p.nii", h.bytes() + std::string(6, '\x05')));
    EXPECT_EQ(v.dims, glm::ivec3(2, 3, 1));
    EXPECT_EQ(v.spacing, glm::dvec3(1.0, 0.75, 2.0));
    EXPECT_EQ(v.value(5), 5.0);
}

// The origin is NIfTI's RAS offset in LPS: x and y negated.
TEST_F(NiftiDetails, OriginFromSformElseQform) {
    NiftiHeader h;
    std::string bytes = h.bytes();
    const std::int16_t one = 1;
    const float qoffset[3] = {1.5f, -2.0f, 3.0f};
    const float srow[12] = {1, 0, 0, -90.0f, 0, 1, 0, 0, 0, 0, 1, 0};
    std::memcpy(&bytes[252], &one, 2); // qform_code
    std::memcpy(&bytes[268], qoffset, 12);
    EXPECT_EQ(readVolume(writeFile("q.nii", bytes + "\x01")).origin, glm::dvec3(-1.5, 2, 3));
    std::memcpy(&bytes[254], &one, 2); // sform_code wins
    std::memcpy(&bytes[280], srow, 48);
    EXPECT_EQ(readVolume(writeFile("s.nii", bytes + "\x01")).origin, glm::dvec3(90, 0, 0));
}

TEST_F(NiftiDetails, DataAfterExtensionsAndOffsetsPastTheEnd) {
    NiftiHeader h;
    h.dims[1] = 4;
    h.voxOffset = 400; // 48 bytes of extensions
    const std::string file = h.bytes() + std::string(48, 'e') + "\x01\x02\x03\x04";
    const Volume v = readVolume(writeFile("ext.nii", file));
    EXPECT_EQ(v.raw(0), 1);
    EXPECT_EQ(v.raw(3), 4);
    EXPECT_EQ(readVolume(writeFile("ext.nii.gz", gzip(file))).raw(3), 4);

    h.voxOffset = 5000;
    for (const std::string name : {"far.nii", "far.nii.gz"}) {
        const std::string bytes = h.bytes() + "\x01\x02\x03\x04";
        const auto path = writeFile(name, name.ends_with(".gz") ? gzip(bytes) : bytes);
        const std::string message = inputError([&] { readVolume(path); });
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find("vox_offset 5000 is beyond the end"), std::string::npos) << message;
    }
}

TEST_F(NiftiDetails, UnsupportedVariantsAreNamed) {
    NiftiHeader pair;
    pair.magic = "ni1";
    std::string message = inputError([&] { readVolume(writeFile("pair.nii", pair.bytes())); });
    EXPECT_NE(message.find("ni1"), std::string::npos) << message;
    NiftiHeader two;
    message = inputError([&] { readVolume(writeFile("two.nii", two.nifti2("ni2"))); });
    EXPECT_NE(message.find("NIfTI-2 header-only"), std::string::npos) << message;
    NiftiHeader complex;
    complex.datatype = 32;
    message = inputError([&] { readVolume(writeFile("c.nii", complex.bytes() + "12345678")); });
    EXPECT_NE(message.find("complex64"), std::string::npos) << message;
}

// NIfTI-2 holds the same fields, wider and elsewhere: the same header read
// either way gives the same volume, byte for byte, in either byte order and
// gzipped; the sform and the qform alike.
TEST_F(NiftiDetails, NiftiTwoReadsAsTheSameNiftiOne) {
    NiftiHeader h;
    h.dims[1] = 3;
    h.dims[2] = 2;
    h.dims[3] = 2;
    h.datatype = 4; // int16
    h.bitpix = 16;
    h.pixdim[1] = 0.5f;
    h.pixdim[2] = 0.75f;
    h.pixdim[3] = 2.0f;
    h.sclSlope = 2.0f;
    h.sclInter = -1024.0f;
    h.sformCode = 1;
    const float srow[3][4] = {{-0.5f, 0, 0, 10}, {0, 0, 0.75f, -20}, {0, 2.0f, 0, 30}};
    std::memcpy(h.srow, srow, sizeof srow);
    std::string data;
    for (std::int16_t v = -6; v < 6; ++v)
        data += bytesOf(&v, 2);
    for (const bool qform : {false, true}) {
        SCOPED_TRACE(qform ? "qform" : "sform");
        if (qform) {
            h.sformCode = 0;
            h.qformCode = 1;
            h.quatern[2] = 0.70710677f; // 90 degrees about z
            h.qoffset[0] = 5.0f;
            h.pixdim[0] = -1.0f; // qfac: the third axis flipped
        }
        const Volume one = readVolume(writeFile("one.nii", h.bytes() + data));
        const Volume two = readVolume(writeFile("two.nii", h.nifti2() + data));
        expectSameVolume(two, one);
        EXPECT_EQ(two.value(0), -6 * 2.0 - 1024.0);
        EXPECT_NE(two.direction, glm::dmat3(1.0)) << "control: the placement was read";
        expectSameVolume(readVolume(writeFile("two.nii.gz", gzip(h.nifti2() + data))), one);
        // The other byte order: every field swapped, by its width.
        std::string big = h.nifti2();
        const auto swapAt = [&](std::size_t at, std::size_t width, std::size_t count) {
            big.replace(at, width * count, byteSwapped(big.substr(at, width * count), width));
        };
        swapAt(0, 4, 1);
        swapAt(12, 2, 2);
        swapAt(16, 8, 8);
        swapAt(104, 8, 8 + 1 + 2 + 2 + 2 + 2);
        swapAt(344, 4, 2);
        swapAt(352, 8, 6 + 12);
        expectSameVolume(readVolume(writeFile("big.nii", big + byteSwapped(data, 2))), one);
    }
}

TEST_F(NiftiDetails, ExtensionsAreMatchedWithoutRegardToCase) {
    NiftiHeader h;
    EXPECT_EQ(readVolume(writeFile("UPPER.NII", h.bytes() + "\x09")).raw(0), 9);
    // Content decides compression: a gzipped file named .nii still reads.
    EXPECT_EQ(readVolume(writeFile("zipped.nii", gzip(h.bytes() + "\x09"))).raw(0), 9);
}

} // namespace cutaway::test
