// DICOM series (volume/dicom.hpp), written by scripts/write_dicom.py (pydicom;
// gdcmconv for JPEG lossless, gdcmgendir for a DICOMDIR) from a volume the
// test makes, and read back to the voxel against it.
#include "core/error.hpp"
#include "volume/dicom.hpp"
#include "volume_test_util.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

constexpr glm::ivec3 kDims{14, 12, 9};
const glm::dvec3 kSpacing(0.8, 0.9, 1.5);
const glm::dvec3 kOrigin(-100.0, -80.0, 40.0); // the script's default

// Values a CT might hold (-1000 .. 1400), multiples of 4 so that every
// rescale below stores them exactly, different along each axis.
Volume source() {
    Volume v = Volume::allocate(kDims, VoxelType::I16, kSpacing);
    for (int z = 0; z < kDims.z; ++z)
        for (int y = 0; y < kDims.y; ++y)
            for (int x = 0; x < kDims.x; ++x) {
                const std::int16_t value =
                    std::int16_t(-1000 + 4 * ((x * 7 + y * 31 + z * 67) % 600));
                std::memcpy(v.data.data() + v.index(x, y, z) * 2, &value, 2);
            }
    return v;
}

class Dicom : public VolumeFiles {
protected:
    // Writes source() as a series into `folder` (under the test's folder).
    fs::path write(const std::string& folder, const std::string& options = {}) {
        const fs::path nrrd = path("source.nrrd");
        if (!fs::exists(nrrd)) writeNrrd(nrrd, source(), false);
        const std::string command = "/usr/bin/python3 " + std::string(CUTAWAY_SOURCE_DIR) +
                                    "/scripts/write_dicom.py " + nrrd.string() + " " +
                                    path(folder).string() + " " + options + " > /dev/null";
        EXPECT_EQ(std::system(command.c_str()), 0) << command;
        return path(folder);
    }
};

void expectSameValues(const Volume& read, const Volume& expected) {
    ASSERT_EQ(read.dims, expected.dims);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < expected.voxelCount(); ++i)
        wrong += read.value(i) != expected.value(i) ? 1 : 0;
    EXPECT_EQ(wrong, 0u) << "voxels that differ from the source";
}

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

// File names and InstanceNumbers at random: the order comes from the
// positions. The geometry is the series': LPS, the script's origin, the
// pixel spacing and the spacing between positions.
TEST_F(Dicom, ShuffledFileNamesReadInPositionOrder) {
    const Volume v = readDicom(write("ct", "--shuffle"));
    expectSameValues(v, source());
    EXPECT_EQ(v.type, VoxelType::I16);
    EXPECT_EQ(v.space, Space::LPS);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(v.spacing[a], kSpacing[a], 1e-5);
        EXPECT_NEAR(v.origin[a], kOrigin[a], 1e-5);
    }
    EXPECT_EQ(v.direction, glm::dmat3(1.0));
    // Control: the files' own order (by name) is not the slices' order.
    std::vector<fs::path> names;
    for (const auto& e : fs::directory_iterator(path("ct")))
        names.push_back(e.path());
    std::sort(names.begin(), names.end());
    const Volume first = readDicom(names.front());
    EXPECT_EQ(first.dims, kDims) << "one file of a series names its whole series";
}

// Stored as uint16 or int16 through RescaleSlope/Intercept: the physical
// values come back, the stored type and the rescale kept.
TEST_F(Dicom, SignedAndUnsignedPixelsWithARescale) {
    const Volume u = readDicom(write("u", "--unsigned --slope 0.5 --intercept -1024"));
    EXPECT_EQ(u.type, VoxelType::U16);
    EXPECT_EQ(u.slope, 0.5);
    EXPECT_EQ(u.inter, -1024.0);
    expectSameValues(u, source());
    const Volume s = readDicom(write("s", "--slope 4 --intercept 200"));
    EXPECT_EQ(s.type, VoxelType::I16);
    EXPECT_EQ(s.slope, 4.0);
    expectSameValues(s, source());
}

// An oblique stack: the volume's directions are the rows', the columns' and
// their normal, and the origin the first slice's position.
TEST_F(Dicom, AnObliqueOrientationGivesTheDirections) {
    const Volume v = readDicom(write("oblique", "--oblique 30 --shuffle"));
    expectSameValues(v, source());
    const double a = 30.0 * std::numbers::pi / 180.0;
    const glm::dvec3 row(std::cos(a), std::sin(a), 0.0);
    const glm::dvec3 column = glm::normalize(
        glm::dvec3(-std::sin(a) * std::cos(a), std::cos(a) * std::cos(a), std::sin(a)));
    const glm::dvec3 normal = glm::cross(row, column);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(v.direction[0][i], row[i], 1e-5);
        EXPECT_NEAR(v.direction[1][i], column[i], 1e-5);
        EXPECT_NEAR(v.direction[2][i], normal[i], 1e-5);
        EXPECT_NEAR(v.origin[i], kOrigin[i], 1e-5);
    }
    EXPECT_NEAR(v.spacing.z, kSpacing.z, 1e-5);
}

TEST_F(Dicom, AJpegLosslessSeriesDecodes) {
    const Volume v = readDicom(write("jpeg", "--jpeg-lossless"));
    expectSameValues(v, source());
}

// Two series in one folder (a localizer beside the CT): no choice is an
// error listing both; a number, a description (any case) or a UID picks one.
TEST_F(Dicom, TwoSeriesInOneFolderArePickedByNumberDescriptionOrUid) {
    write("study/ct", "--series-number 3 --description 'CT head' --uid 1.2.3.4.5");
    write("study/localizer", "--series-number 1 --description Localizer --oblique 10");
    const fs::path study = path("study");
    const std::string message = messageOf([&] { readDicom(study); });
    EXPECT_NE(message.find("holds 2 series"), std::string::npos) << message;
    EXPECT_NE(message.find("\"CT head\""), std::string::npos) << message;
    EXPECT_NE(message.find("\"Localizer\""), std::string::npos) << message;
    EXPECT_EQ(readDicom(study, "3").direction, glm::dmat3(1.0));
    EXPECT_EQ(readDicom(study, "ct HEAD").direction, glm::dmat3(1.0));
    EXPECT_EQ(readDicom(study, "1.2.3.4.5").direction, glm::dmat3(1.0));
    EXPECT_NE(readDicom(study, "localizer").direction, glm::dmat3(1.0));
    const std::string none = messageOf([&] { readDicom(study, "7"); });
    EXPECT_NE(none.find("no series matches \"7\""), std::string::npos) << none;
    const DicomListing listing = listDicom(study);
    ASSERT_EQ(listing.series.size(), 2u);
    EXPECT_EQ(listing.series[0].number, "1"); // ordered by number
    EXPECT_EQ(listing.series[1].dims, kDims);
}

// A file that is not DICOM is passed over; a truncated slice is an error
// naming it.
TEST_F(Dicom, AForeignFileIsPassedOverATruncatedSliceRefused) {
    const fs::path folder = write("ct");
    writeFile("ct/README.txt", "not an image");
    expectSameValues(readDicom(folder), source());
    EXPECT_EQ(listDicom(folder).ignored, 1u);
    const fs::path cut = write("cut", "--truncate-slice 4");
    const std::string message = messageOf([&] { readDicom(cut); });
    EXPECT_NE(message.find("slice0004.dcm"), std::string::npos) << message;
}

// A DICOM file cut short in its header (here 128 zeros and "DICM") reaches
// an assertion in GDCM's reader. GDCM parses in a child process, so that is an error naming
// the file, not an abort of cutaway. Control: the same parse in this process
// dies of the assertion (a death test).
TEST_F(Dicom, AHeaderCutShortIsRefusedNotAnAbort) {
    fs::create_directories(path("stub"));
    writeFile("stub/stub.dcm", std::string(128, '\0') + "DICM");
    const fs::path stub = path("stub/stub.dcm");
    for (const fs::path& named : {stub, path("stub")}) {
        SCOPED_TRACE(named.string());
        const std::string listed = messageOf([&] { listDicom(named); });
        EXPECT_NE(listed.find(stub.string() + ": a damaged or truncated DICOM file"),
                  std::string::npos)
            << listed;
        const std::string read = messageOf([&] { readDicom(named); });
        EXPECT_NE(read.find(stub.string() + ": a damaged or truncated DICOM file"),
                  std::string::npos)
            << read;
    }
    // A slice cut inside an element is refused before GDCM reads it (volume/
    // dicom_lengths.hpp), naming the element.
    const fs::path folder = write("series");
    fs::resize_file(folder / "slice0003.dcm", 300);
    const std::string cut = messageOf([&] { readDicom(folder); });
    EXPECT_NE(cut.find("slice0003.dcm: its element (0002,0012) declares 28 bytes where the file "
                       "holds 0 after it (cut short, or damaged)"),
              std::string::npos)
        << cut;

    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(detail::listDicomHere(stub), "") << "control: GDCM aborts on it in-process";
}

// Runs a pydicom edit of `file` (Python statements on the dataset `d`).
void editDicom(const fs::path& file, const std::string& statements) {
    const std::string command =
        "/usr/bin/python3 -W ignore -c \"import pydicom; d = pydicom.dcmread('" + file.string() +
        "'); " + statements + "; d.save_as('" + file.string() + "')\"";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

// Pixel data shorter than Rows x Columns (GDCM pads it with zeros), or a
// slice cut short inside its pixels, is refused naming the file; so is a
// PixelSpacing that is not two finite spacings (GDCM reads uninitialised
// memory on "nan"), however the folder is spelled. Controls: the untouched
// series reads, and reads alike through a path spelled another way.
TEST_F(Dicom, ShortPixelDataAndBadSpacingAreRefused) {
    const fs::path rows = write("rows");
    editDicom(rows / "slice0000.dcm", "d.Rows = d.Rows + 2");
    std::string message = messageOf([&] { readDicom(rows); });
    EXPECT_NE(message.find("slice0000.dcm: its pixel data holds 336 bytes where 14 x 14 pixels"),
              std::string::npos)
        << message;

    const fs::path cut = write("cut");
    fs::resize_file(cut / "slice0006.dcm", fs::file_size(cut / "slice0006.dcm") - 40);
    message = messageOf([&] { readDicom(cut); });
    EXPECT_NE(message.find("slice0006.dcm: its pixel data holds 296 bytes"), std::string::npos)
        << message;

    const fs::path nan = write("nan");
    for (const auto& entry : fs::directory_iterator(nan))
        editDicom(entry.path(), "d.PixelSpacing = ['nan', 'nan']");
    for (const fs::path& spelled : {nan, fs::path(nan.string() + "/."), nan / "sub" / ".."}) {
        SCOPED_TRACE(spelled.string());
        if (spelled.filename() == "..") fs::create_directories(nan / "sub");
        message = messageOf([&] { readDicom(spelled); });
        EXPECT_NE(message.find("PixelSpacing 'nan\\nan' is not two finite spacings"),
                  std::string::npos)
            << message;
    }
    const fs::path fine = write("fine");
    expectSameValues(readDicom(fs::path(fine.string() + "/.")), source());
}

// A SeriesDescription holding a terminal escape sequence is listed escaped.
TEST_F(Dicom, TagsAreListedEscaped) {
    const fs::path folder = write("ct");
    for (const auto& entry : fs::directory_iterator(folder))
        editDicom(entry.path(), "d.SeriesDescription = chr(27) + ']0;owned' + chr(7)");
    const std::string listed = describeSeries(listDicom(folder));
    EXPECT_EQ(listed.find('\x1b'), std::string::npos) << listed;
    EXPECT_NE(listed.find("\"\\x1b]0;owned\\x07\""), std::string::npos) << listed;
}

// A file of a few hundred bytes whose header claims 40000 x 40000 pixels is
// refused by its pixel data's length, before its pixels are allocated (3.2 GB
// each, which took 11-25 s); a series
// whose slices claim more than a volume may hold is refused before its
// first slice is read.
TEST_F(Dicom, SizesAreCheckedBeforeMemoryIsTaken) {
    const fs::path folder = write("huge");
    for (int k = 0; k < kDims.z; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "slice%04d.dcm", k);
        editDicom(folder / name, "d.Rows = 40000; d.Columns = 40000");
    }
    const std::string series = messageOf([&] { readDicom(folder); });
    EXPECT_NE(series.find("exceeds the limit of 2^31 voxels"), std::string::npos) << series;
    fs::remove_all(folder);
    fs::create_directories(folder);
    fs::copy_file(write("one") / "slice0000.dcm", folder / "only.dcm");
    editDicom(folder / "only.dcm", "d.Rows = 40000; d.Columns = 40000");
    const std::string one = messageOf([&] { readDicom(folder); });
    EXPECT_NE(one.find("only.dcm: its pixel data holds 336 bytes where 40000 x 40000"),
              std::string::npos)
        << one;
}

// GDCM sizes a value's buffer by its declared length before it reads it: a
// length past the file's end is refused first (volume/dicom_lengths.hpp),
// so a slice declaring 2 GiB of pixel data takes no memory for them.
// Control: the same slice as written reads.
TEST_F(Dicom, DeclaredLengthsPastTheEndAreRefusedBeforeGdcmReads) {
    const fs::path folder = write("long");
    EXPECT_EQ(messageOf([&] { readDicom(folder); }), "(no error)");
    // The pixel data's 4-byte length lies just before its 14 x 12 int16 pixels.
    const fs::path slice = folder / "slice0004.dcm";
    const std::uint64_t lengthAt = fs::file_size(slice) - 14 * 12 * 2 - 4;
    std::fstream file(slice, std::ios::binary | std::ios::in | std::ios::out);
    const unsigned char length[4] = {0xf0, 0xff, 0xff, 0x7f}; // 2147483632
    file.seekp(std::streamoff(lengthAt));
    file.write(reinterpret_cast<const char*>(length), 4);
    file.close();
    const std::string message = messageOf([&] { readDicom(folder); });
    EXPECT_NE(message.find("slice0004.dcm: its pixel data holds 336 bytes where it declares "
                           "2147483632 (cut short, or damaged)"),
              std::string::npos)
        << message;
}

// Symbolic links: one to the folder's parent and one to the folder itself
// (which a walk that follows them never leaves), one to a file outside the
// folder and one to a slice beside it. None is followed: the series reads
// back once, each slice once. Control: a real subfolder is still searched
// (its second series is listed).
TEST_F(Dicom, LinksAreNotFollowedOutOfTheFolderOrIntoLoops) {
    const fs::path folder = write("ct");
    fs::create_directory_symlink("..", folder / "up");
    fs::create_directory_symlink(".", folder / "self");
    writeFile("outside.dcm", "a file beside the folder");
    fs::create_symlink(path("outside.dcm"), folder / "outside.dcm");
    fs::create_symlink("slice0002.dcm", folder / "again.dcm");
    const DicomListing listing = listDicom(folder);
    ASSERT_EQ(listing.series.size(), 1u);
    EXPECT_EQ(listing.series[0].files.size(), std::size_t(kDims.z)) << "each slice once";
    expectSameValues(readDicom(folder), source());

    const fs::path sub = folder / "sub";
    const std::string command = "/usr/bin/python3 " + std::string(CUTAWAY_SOURCE_DIR) +
                                "/scripts/write_dicom.py " + path("source.nrrd").string() + " " +
                                sub.string() + " --series-number 2 > /dev/null";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    EXPECT_EQ(listDicom(folder).series.size(), 2u) << "control: subfolders are searched";
}

// A stack that is not one regular grid is refused, saying why.
TEST_F(Dicom, IrregularStacksAreRefused) {
    const std::string missing = messageOf([&] { readDicom(write("gap", "--skip-slice 4")); });
    EXPECT_NE(missing.find("slices missing between"), std::string::npos) << missing;
    const std::string uneven = messageOf([&] { readDicom(write("uneven", "--skew 0.2")); });
    EXPECT_NE(uneven.find("uneven slice spacing"), std::string::npos) << uneven;
    const std::string tilt = messageOf([&] { readDicom(write("tilt", "--tilt 0.4")); });
    EXPECT_NE(tilt.find("gantry tilt"), std::string::npos) << tilt;
    fs::create_directories(path("empty"));
    writeFile("empty/notes.txt", "no images here");
    const std::string empty = messageOf([&] { readDicom(path("empty")); });
    EXPECT_NE(empty.find("no DICOM image found"), std::string::npos) << empty;
}

// A DICOMDIR names the series of the folder it indexes.
TEST_F(Dicom, ADicomdirReadsItsSeries) {
    const fs::path folder = write("disc", "--shuffle --media-names");
    const std::string command =
        "cd " + folder.string() + " && gdcmgendir -i . -o DICOMDIR > /dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    expectSameValues(readDicom(folder / "DICOMDIR"), source());
    EXPECT_TRUE(isDicomPath(folder / "DICOMDIR"));
    EXPECT_FALSE(isDicomPath(path("source.nrrd")));
}

// The same checks on a real scan, the shared CT head (64 x 64 x 93 uint16,
// 3.2 x 3.2 x 1.5 mm): shuffled JPEG-lossless files of unsigned pixels with a
// rescale, and a signed oblique series as scanners store CT (intercept -1024).
TEST_F(Dicom, ASharedScanReadsBackToTheVoxel) {
    const fs::path scan = fs::path(CUTAWAY_SOURCE_DIR) / ".." / "shared" / "data" / "headsq.nrrd";
    if (!fs::exists(scan)) GTEST_SKIP() << scan << " not found: the shared scans are absent";
    const Volume expected = readVolume(scan);
    const std::string script = std::string(CUTAWAY_SOURCE_DIR) + "/scripts/write_dicom.py ";
    for (const char* options : {"--shuffle --unsigned --slope 1 --intercept -1024 --jpeg-lossless",
                                "--slope 1 --intercept -1024 --oblique 20"}) {
        SCOPED_TRACE(options);
        const fs::path folder =
            path(std::string(options).find("oblique") != std::string::npos ? "oblique" : "jpeg");
        const std::string command = "/usr/bin/python3 " + script + scan.string() + " " +
                                    folder.string() + " " + options + " > /dev/null";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        const Volume v = readDicom(folder);
        expectSameValues(v, expected);
        EXPECT_NEAR(v.spacing.x, 3.2, 1e-6);
        EXPECT_NEAR(v.spacing.z, 1.5, 1e-6);
        // The series' files are what a run reads: the folder and each slice.
        EXPECT_EQ(volumeFiles(folder).size(), std::size_t(expected.dims.z) + 1);
    }
}

} // namespace
} // namespace cutaway::test
