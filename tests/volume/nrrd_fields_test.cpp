// NRRD header details beyond the basic round trips: every type spelling of the
// spec, skips, line endings, key/value pairs, the writer's optional fields,
// and the limits a header may not exceed.
#include "volume_test_util.hpp"

#include <cmath>
#include <iterator>

namespace cutaway::test {
namespace {

std::string header(const std::string& type, const std::string& extra,
                   const std::string& encoding = "raw") {
    return "NRRD0004\ntype: " + type + "\ndimension: 3\nsizes: 2 2 2\nencoding: " + encoding +
           "\nendian: little\n" + extra;
}

/// The text of a NRRD file's header, up to its blank line.
std::string headerText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    return text.substr(0, text.find("\n\n") + 1);
}

void expectNear(glm::dvec3 got, glm::dvec3 want, double tolerance, const std::string& what) {
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(got[a], want[a], tolerance) << what << " [" << a << "]";
}

/// A 5 x 4 x 3 uint8 volume, each voxel its index.
Volume indexed(glm::dvec3 spacing) {
    Volume v = Volume::allocate({5, 4, 3}, VoxelType::U8, spacing);
    for (std::size_t i = 0; i < v.voxelCount(); ++i)
        v.data[i] = std::byte(i);
    return v;
}

} // namespace

using NrrdFields = VolumeFiles;

TEST_F(NrrdFields, EveryTypeSpellingOfTheSpec) {
    const std::pair<const char*, VoxelType> spellings[] = {
        {"signed char", VoxelType::I8},
        {"int8", VoxelType::I8},
        {"int8_t", VoxelType::I8},
        {"uchar", VoxelType::U8},
        {"unsigned char", VoxelType::U8},
        {"uint8", VoxelType::U8},
        {"uint8_t", VoxelType::U8},
        {"short", VoxelType::I16},
        {"short int", VoxelType::I16},
        {"signed short", VoxelType::I16},
        {"signed short int", VoxelType::I16},
        {"int16", VoxelType::I16},
        {"int16_t", VoxelType::I16},
        {"ushort", VoxelType::U16},
        {"unsigned short", VoxelType::U16},
        {"unsigned short int", VoxelType::U16},
        {"uint16", VoxelType::U16},
        {"uint16_t", VoxelType::U16},
        {"int", VoxelType::I32},
        {"signed int", VoxelType::I32},
        {"int32", VoxelType::I32},
        {"int32_t", VoxelType::I32},
        {"uint", VoxelType::U32},
        {"unsigned int", VoxelType::U32},
        {"uint32", VoxelType::U32},
        {"uint32_t", VoxelType::U32},
        {"float", VoxelType::F32},
        {"double", VoxelType::F64},
    };
    for (const auto& [spelling, type] : spellings) {
        SCOPED_TRACE(spelling);
        const std::string data(8 * voxelSize(type), '\0');
        const Volume v = readVolume(writeFile("t.nrrd", header(spelling, "\n") + data));
        EXPECT_EQ(v.type, type) << voxelTypeName(v.type);
    }
    // 64-bit integers are NRRD types cutaway does not read: said so, not "unknown".
    const std::string message =
        inputError([&] { readVolume(writeFile("i64.nrrd", header("int64", "\n"))); });
    EXPECT_NE(message.find("unsupported type 'int64'"), std::string::npos) << message;
}

TEST_F(NrrdFields, CommentsKeyValuesCrlfAndFieldOrder) {
    // sizes before dimension, CRLF line ends, blanks around values, key:=value pairs.
    const std::string text = "NRRD0003\r\n# made by hand\r\nsizes:  2 1 1 \r\ntype:   unsigned   "
                             "short\r\nmy key:=a: b\r\ndimension: 3\r\ncontent: test\r\nencoding: "
                             "raw\r\nendian: big\r\n\r\n";
    const Volume v = readVolume(writeFile("crlf.nrrd", text + std::string("\x12\x34\xab\xcd", 4)));
    EXPECT_EQ(v.dims, glm::ivec3(2, 1, 1));
    EXPECT_EQ(v.raw(0), 0x1234);
    EXPECT_EQ(v.raw(1), 0xabcd);
}

TEST_F(NrrdFields, LineSkipAndByteSkip) {
    // Detached raw data after two text lines and three bytes.
    writeFile("d.raw",
              "first line\nsecond line\nxyz" + std::string("\x01\x02\x03\x04\x05\x06\x07\x08"));
    writeFile("d.nhdr", header("uint8", "line skip: 2\nbyte skip: 3\ndata file: d.raw\n"));
    const Volume v = readVolume(path("d.nhdr"));
    EXPECT_EQ(v.raw(0), 1);
    EXPECT_EQ(v.raw(7), 8);

    // For gzip the byte skip counts decompressed bytes.
    writeFile("g.nrrd", header("uint8", "byte skip: 4\n\n", "gz") +
                            gzip("skip" + std::string("\x09\x08\x07\x06\x05\x04\x03\x02")));
    const Volume g = readVolume(path("g.nrrd"));
    EXPECT_EQ(g.raw(0), 9);
    EXPECT_EQ(g.raw(7), 2);

    const std::string message = inputError(
        [&] { readVolume(writeFile("bad.nrrd", header("uint8", "byte skip: -1\n\n", "gzip"))); });
    EXPECT_NE(message.find("byte skip -1"), std::string::npos) << message;
    const std::string past = inputError([&] {
        writeFile("few.raw", "one line\n");
        readVolume(writeFile("few.nhdr", header("uint8", "line skip: 5\ndata file: few.raw\n")));
    });
    EXPECT_NE(past.find("line skip 5"), std::string::npos) << past;
}

TEST_F(NrrdFields, RawDataLongerThanDeclaredIsFineGzipIsNot) {
    const Volume v =
        readVolume(writeFile("long.nrrd", header("uint8", "\n") + std::string(8, '\x07') + "tail"));
    EXPECT_EQ(v.raw(7), 7);
    const auto file =
        writeFile("long-gz.nrrd", header("uint8", "\n", "gzip") + gzip(std::string(9, '\x07')));
    const std::string message = inputError([&] { readVolume(file); });
    EXPECT_NE(message.find("long-gz.nrrd"), std::string::npos) << message;
    EXPECT_NE(message.find("exceeds the declared size"), std::string::npos) << message;
}

TEST_F(NrrdFields, ConcatenatedGzipMembersAreOneStream) {
    const auto file = writeFile("two.nrrd", header("uint8", "\n", "gzip") + gzip("\x01\x02\x03") +
                                                gzip(std::string("\x04\x05\x06\x07\x08")));
    const Volume v = readVolume(file);
    EXPECT_EQ(v.raw(0), 1);
    EXPECT_EQ(v.raw(7), 8);
}

TEST_F(NrrdFields, WriterKeepsOriginAndScaling) {
    Volume v = Volume::allocate({3, 2, 2}, VoxelType::I16, {0.5, 0.25, 4.0});
    v.origin = {-10.5, 20.0, 3.25};
    v.slope = 0.5;
    v.inter = -1024.0;
    reinterpret_cast<std::int16_t*>(v.data.data())[5] = -300;
    writeNrrd(path("o.nrrd"), v);
    const Volume got = readVolume(path("o.nrrd"));
    EXPECT_EQ(got.origin, v.origin);
    EXPECT_EQ(got.spacing, v.spacing);
    EXPECT_EQ(got.value(5), -300 * 0.5 - 1024.0);
    EXPECT_EQ(got.value(0), -1024.0);
}

// An oblique LPS orientation (a rotation about z by 30 degrees, then the k
// axis flipped) survives writing and reading: same directions, spacing,
// origin and space, written as a space with space directions, no spacings.
TEST_F(NrrdFields, WriterKeepsAnLpsOrientation) {
    Volume v = indexed({0.5, 1.25, 3.0});
    const double c = std::cos(glm::radians(30.0)), s = std::sin(glm::radians(30.0));
    v.direction = glm::dmat3(glm::dvec3(c, s, 0), glm::dvec3(-s, c, 0), glm::dvec3(0, 0, -1));
    v.origin = {-10.5, 20.0, 3.25};
    v.space = Space::LPS;
    writeNrrd(path("lps.nrrd"), v, false);
    const std::string text = headerText(path("lps.nrrd"));
    EXPECT_NE(text.find("space: left-posterior-superior\n"), std::string::npos) << text;
    EXPECT_NE(text.find("space directions: ("), std::string::npos) << text;
    EXPECT_NE(text.find("space origin: (-10.5,20,3.25)\n"), std::string::npos) << text;
    EXPECT_NE(text.find("(0,0,-3)\n"), std::string::npos) << "k runs inferior: " << text;
    EXPECT_EQ(text.find("spacings"), std::string::npos) << text;
    EXPECT_EQ(text.find("space dimension"), std::string::npos) << "not both: " << text;

    const Volume got = readVolume(path("lps.nrrd"));
    EXPECT_EQ(got.space, Space::LPS);
    expectNear(got.spacing, v.spacing, 1e-12, "spacing");
    for (int a = 0; a < 3; ++a)
        expectNear(got.direction[a], v.direction[a], 1e-12, "direction " + std::to_string(a));
    EXPECT_EQ(got.origin, v.origin);
    // The far corner voxel's centre, by hand: origin + 4 * 0.5 * i-direction
    // + 3 * 1.25 * j-direction - 2 * 3 * z.
    const glm::dvec3 corner(-10.5 + 2.0 * c - 3.75 * s, 20.0 + 2.0 * s + 3.75 * c, 3.25 - 6.0);
    expectNear(got.physicalPosition({4, 3, 2}), corner, 1e-9, "corner");
    for (std::size_t i = 0; i < v.voxelCount(); ++i)
        ASSERT_EQ(got.raw(i), v.raw(i)) << i;

    // Written again, the same header.
    writeNrrd(path("again.nrrd"), got, false);
    EXPECT_EQ(headerText(path("again.nrrd")), text);
}

// A RAS (and a LAS) file reads into LPS: x and y (y only) negated, for the
// directions and the origin. The axes are permuted and flipped: i runs
// anterior, j to the right's opposite (left), k inferior.
TEST_F(NrrdFields, RasAndLasSpacesReadIntoLps) {
    const std::string geometry = "sizes: 5 4 3\nspace directions: (0,2,0) (-3,0,0) (0,0,-0.5)\n"
                                 "space origin: (10,20,30)\nencoding: raw\n\n" +
                                 std::string(60, '\x01');
    const auto read = [&](const std::string& name, const std::string& space) {
        return readVolume(writeFile(name, "NRRD0004\ntype: uint8\ndimension: 3\nspace: " + space +
                                              "\n" + geometry));
    };
    // Voxel (4, 3, 2) in the file's space: (10, 20, 30) + 4 (0,2,0) + 3 (-3,0,0)
    // + 2 (0,0,-0.5) = (1, 28, 29); in LPS (-1, -28, 29) from RAS, (1, -28, 29)
    // from LAS.
    for (const char* spelling : {"right-anterior-superior", "RAS", "Right Anterior Superior"}) {
        SCOPED_TRACE(spelling);
        const Volume ras = read("ras.nrrd", spelling);
        EXPECT_EQ(ras.space, Space::LPS);
        EXPECT_EQ(ras.spacing, glm::dvec3(2, 3, 0.5));
        EXPECT_EQ(ras.origin, glm::dvec3(-10, -20, 30));
        EXPECT_EQ(ras.direction[0], glm::dvec3(0, -1, 0));
        EXPECT_EQ(ras.direction[1], glm::dvec3(1, 0, 0));
        EXPECT_EQ(ras.direction[2], glm::dvec3(0, 0, -1));
        expectNear(ras.physicalPosition({4, 3, 2}), {-1, -28, 29}, 1e-12, "RAS corner");
    }
    const Volume las = read("las.nrrd", "left-anterior-superior");
    EXPECT_EQ(las.space, Space::LPS);
    EXPECT_EQ(las.origin, glm::dvec3(10, -20, 30));
    expectNear(las.physicalPosition({4, 3, 2}), {1, -28, 29}, 1e-12, "LAS corner");

    // Written back: LPS, the same physical positions.
    writeNrrd(path("back.nrrd"), read("ras.nrrd", "RAS"), false);
    const std::string text = headerText(path("back.nrrd"));
    EXPECT_NE(text.find("space: left-posterior-superior\n"), std::string::npos) << text;
    EXPECT_NE(text.find("space directions: (0,-2,0) (3,0,0) (0,0,-0.5)\n"), std::string::npos)
        << text;
    EXPECT_NE(text.find("space origin: (-10,-20,30)\n"), std::string::npos) << text;

    // A time space: the spatial part of 4-component vectors.
    const Volume rast = readVolume(
        writeFile("rast.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nspace: RAST\nsizes: 5 4 3\n"
                               "space directions: (0,2,0,0) (-3,0,0,0) (0,0,-0.5,0)\n"
                               "space origin: (10,20,30,7)\nencoding: raw\n\n" +
                                   std::string(60, '\x01')));
    EXPECT_EQ(rast.space, Space::LPS);
    expectNear(rast.physicalPosition({4, 3, 2}), {-1, -28, 29}, 1e-12, "RAST corner");
}

// scanner-xyz, 3D-right-handed and a bare `space dimension: 3` have no
// anatomy: their vectors are kept as written, and written back with
// `space dimension: 3`.
TEST_F(NrrdFields, NonAnatomicalSpacesKeepTheirVectors) {
    for (const char* space : {"space: scanner-xyz", "space: 3D-right-handed",
                              "space: 3D-left-handed", "space dimension: 3"}) {
        SCOPED_TRACE(space);
        const Volume v = readVolume(writeFile(
            "n.nrrd", std::string("NRRD0004\ntype: uint8\ndimension: 3\n") + space +
                          "\nsizes: 5 4 3\nspace directions: (0,2,0) (-3,0,0) (0,0,-0.5)\n"
                          "space origin: (10,20,30)\nencoding: raw\n\n" +
                          std::string(60, '\x01')));
        EXPECT_EQ(v.space, Space::NonAnatomical);
        EXPECT_EQ(v.origin, glm::dvec3(10, 20, 30));
        EXPECT_EQ(v.direction[0], glm::dvec3(0, 1, 0));
        EXPECT_EQ(v.direction[1], glm::dvec3(-1, 0, 0));
        expectNear(v.physicalPosition({4, 3, 2}), {1, 28, 29}, 1e-12, "corner");
        writeNrrd(path("back.nrrd"), v, false);
        const std::string text = headerText(path("back.nrrd"));
        EXPECT_NE(text.find("space dimension: 3\nspace directions: (0,2,0) (-3,0,0) (0,0,-0.5)\n"
                            "space origin: (10,20,30)\n"),
                  std::string::npos)
            << text;
        EXPECT_EQ(text.find("space:"), std::string::npos) << text;
    }
    // Without any orientation: `spacings`, as before.
    writeNrrd(path("plain.nrrd"), indexed({1, 2, 3}), false);
    const std::string plain = headerText(path("plain.nrrd"));
    EXPECT_NE(plain.find("spacings: 1 2 3\n"), std::string::npos) << plain;
    EXPECT_EQ(plain.find("space"), std::string::npos) << plain;
    EXPECT_EQ(readVolume(path("plain.nrrd")).space, Space::None);
}

TEST_F(NrrdFields, BadSpacesAreRefused) {
    const auto message = [&](const std::string& space, const std::string& directions) {
        return inputError([&] {
            readVolume(writeFile("bad.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\n" + space +
                                                 "sizes: 2 2 2\nspace directions: " + directions +
                                                 "\nencoding: raw\n\n" + std::string(8, '\0')));
        });
    };
    const std::string unknown = message("space: RAI\n", "(1,0,0) (0,1,0) (0,0,1)");
    EXPECT_NE(unknown.find("unknown space 'RAI'"), std::string::npos) << unknown;
    const std::string components = message("space: LPS\n", "(1,0) (0,1) (0,0)");
    EXPECT_NE(components.find("2 components but the space has 3"), std::string::npos) << components;
    const std::string dimension = message("space dimension: 2\n", "(1,0) (0,1) (0,0)");
    EXPECT_NE(dimension.find("space dimension 2"), std::string::npos) << dimension;
    const std::string contradiction =
        message("space: LPS\nspace dimension: 4\n", "(1,0,0) (0,1,0) (0,0,1)");
    EXPECT_NE(contradiction.find("contradicts"), std::string::npos) << contradiction;
    const std::string zero = message("space: LPS\n", "(1,0,0) (0,0,0) (0,0,1)");
    EXPECT_NE(zero.find("spacing"), std::string::npos) << zero;
}

TEST_F(NrrdFields, WriterFailureNamesThePath) {
    const Volume v = Volume::allocate({2, 2, 2}, VoxelType::U8);
    const auto target = path("no-such-folder/out.nrrd");
    try {
        writeNrrd(target, v);
        FAIL() << "no error";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(target));
}

TEST_F(NrrdFields, LimitsOnDeclaredSizes) {
    const auto message = [&](const std::string& name, const std::string& sizes,
                             const std::string& type = "uint8") {
        return inputError([&] {
            readVolume(writeFile(name, "NRRD0004\ntype: " + type + "\ndimension: 3\nsizes: " +
                                           sizes + "\nencoding: raw\n\n"));
        });
    };
    EXPECT_NE(message("huge.nrrd", "100000 100000 100000").find("too large"), std::string::npos);
    EXPECT_NE(message("overflow.nrrd", "99999999999999999999 1 1").find("not an integer"),
              std::string::npos);
    // Within the 2^31 voxel limit, beyond 8 GiB of doubles.
    EXPECT_NE(message("bytes.nrrd", "1024 1024 1025", "double").find("8 GiB"), std::string::npos);
    // Within the limits but with no data: truncated, without allocating 1 GiB first.
    EXPECT_NE(message("empty.nrrd", "1024 1024 1024").find("truncated"), std::string::npos);
}

TEST_F(NrrdFields, UnsupportedDataFileForms) {
    const std::string list = inputError([&] {
        readVolume(writeFile("list.nhdr", header("uint8", "data file: LIST\na.raw\nb.raw\n")));
    });
    EXPECT_NE(list.find("not supported"), std::string::npos) << list;
    const std::string format = inputError([&] {
        readVolume(writeFile("fmt.nhdr", header("uint8", "data file: slice%03d.raw 1 2 1\n")));
    });
    EXPECT_NE(format.find("not supported"), std::string::npos) << format;
    const std::string dim4 = inputError([&] {
        readVolume(writeFile("rgb.nrrd", "NRRD0004\ntype: uint8\ndimension: 4\nsizes: 3 2 2 2\n"
                                         "encoding: raw\n\n"));
    });
    EXPECT_NE(dim4.find("first axis of size 1"), std::string::npos) << dim4;
}

} // namespace cutaway::test
