// Hostile and broken volume files end in an InputError that names the file
// and says what is wrong; never a crash, a hang or a huge allocation.
#include "io/named_pipe.hpp"
#include "volume_test_util.hpp"

namespace cutaway::test {
namespace {

const std::string kGood = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n";

struct Case {
    const char* name;
    std::string content;
    const char* phrase; // a distinctive part of the expected message
};

} // namespace

using MalformedVolumes = VolumeFiles;

TEST_F(MalformedVolumes, NrrdProblemsAreNamed) {
    const std::string data64(64, '\x01');
    const std::vector<Case> cases = {
        {"truncated.nrrd", kGood + "\n" + std::string(40, '\x01'), "data truncated"},
        {"truncated-gz.nrrd",
         "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: gzip\n\n" +
             gzip(std::string(40, '\x01')),
         "truncated"},
        {"corrupt-gz.nrrd",
         "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: gzip\n\n" +
             std::string(100, '\x55'),
         ""},
        {"bzip2.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: bzip2\n\n",
         "unsupported encoding 'bzip2'"},
        {"ascii.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: ascii\n\n",
         "unsupported encoding"},
        {"type.nrrd", "NRRD0004\ntype: complex\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n",
         "type 'complex'"},
        {"sizes-count.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4\nencoding: raw\n\n",
         "'sizes' has 2"},
        {"size-zero.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 0 4\nencoding: raw\n\n",
         "sizes"},
        {"size-negative.nrrd",
         "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 -3 4\nencoding: raw\n\n", "sizes"},
        {"absurd.nrrd",
         "NRRD0004\ntype: float\ndimension: 3\nsizes: 100000 100000 100000\nencoding: raw\n\n", ""},
        {"spacing-nan.nrrd", kGood + "spacings: 1 nan 1\n\n" + data64, "spacing"},
        {"spacing-inf.nrrd", kGood + "spacings: 1 1 inf\n\n" + data64, "spacing"},
        {"spacing-negative.nrrd", kGood + "spacings: -1 1 1\n\n" + data64, "spacing"},
        {"spacing-zero.nrrd", kGood + "spacings: 1 0 1\n\n" + data64, "spacing"},
        {"dimension-2.nrrd", "NRRD0004\ntype: uint8\ndimension: 2\nsizes: 4 4\nencoding: raw\n\n",
         "dimension 2"},
        {"magic.nrrd", "PNRRD\ntype: uint8\n\n", "not a NRRD file"},
        {"empty.nrrd", "", "empty file"},
        {"endian.nrrd", kGood + "endian: middle\n\n" + data64, "endian 'middle'"},
        {"missing-data.nhdr", kGood + "data file: nowhere.raw\n", "nowhere.raw"},
        {"no-blank-line.nrrd", kGood, "no data"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const auto file = writeFile(c.name, c.content);
        const std::string message = inputError([&] { readVolume(file); });
        ASSERT_FALSE(message.empty()) << "read without error";
        EXPECT_NE(message.find(c.name), std::string::npos) << message;
        EXPECT_NE(message.find(c.phrase), std::string::npos) << message;
    }
}

TEST_F(MalformedVolumes, GzipBombIsRefusedAtTheDeclaredSize) {
    // 16^3 = 4 KiB declared, 64 MiB of zeros inside ~64 KiB of gzip.
    const std::string bomb = gzip(std::string(64u << 20, '\0'));
    ASSERT_LT(bomb.size(), 200000u);
    const auto nrrd = writeFile(
        "bomb.nrrd",
        "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: gzip\n\n" + bomb);
    const std::string message = inputError([&] { readVolume(nrrd); });
    EXPECT_NE(message.find("exceeds the declared size"), std::string::npos) << message;

    NiftiHeader h;
    h.dims[1] = h.dims[2] = h.dims[3] = 16;
    const auto nii = writeFile("bomb.nii.gz", gzip(h.bytes() + std::string(64u << 20, '\0')));
    EXPECT_NE(inputError([&] { readVolume(nii); }).find("bomb.nii.gz"), std::string::npos);
}

TEST_F(MalformedVolumes, NiftiProblemsAreNamed) {
    auto withHeader = [](auto edit, std::size_t dataBytes = 8) {
        NiftiHeader h;
        h.dims[1] = 2;
        h.dims[2] = 2;
        h.dims[3] = 2;
        edit(h);
        return h.bytes() + std::string(dataBytes, '\x02');
    };
    const std::vector<Case> cases = {
        {"sizeof.nii", withHeader([](NiftiHeader& h) { h.sizeofHdr = 100; }), "sizeof_hdr is 100"},
        {"negative-dim.nii", withHeader([](NiftiHeader& h) { h.dims[2] = -4; }), "dim[2] is -4"},
        {"zero-dim.nii", withHeader([](NiftiHeader& h) { h.dims[3] = 0; }), "dim[3] is 0"},
        {"rank-2.nii", withHeader([](NiftiHeader& h) { h.dims[0] = 2; }), "2-dimensional"},
        {"time-series.nii", withHeader([](NiftiHeader& h) {
             h.dims[0] = 4;
             h.dims[4] = 5;
         }),
         "dim[4] is 5"},
        {"rgb.nii", withHeader([](NiftiHeader& h) { h.datatype = 128; }), "datatype 128"},
        {"offset-past-end.nii", withHeader([](NiftiHeader& h) { h.voxOffset = 1e6f; }), ""},
        {"offset-nan.nii", withHeader([](NiftiHeader& h) { h.voxOffset = std::nanf(""); }),
         "vox_offset"},
        {"magic.nii", withHeader([](NiftiHeader& h) { h.magic = "xyz"; }), "magic"},
        {"truncated.nii", withHeader([](NiftiHeader&) {}, 3), "truncated"},
        {"short.nii", std::string(100, '\0'), ""},
        {"spacing-inf.nii", withHeader([](NiftiHeader& h) { h.pixdim[2] = INFINITY; }), "spacing"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const auto file = writeFile(c.name, c.content);
        const std::string message = inputError([&] { readVolume(file); });
        ASSERT_FALSE(message.empty()) << "read without error";
        EXPECT_NE(message.find(c.name), std::string::npos) << message;
        EXPECT_NE(message.find(c.phrase), std::string::npos) << message;
        // Gzipped, the same problems are found the same way.
        const auto gz = writeFile(std::string(c.name) + ".gz", gzip(c.content));
        EXPECT_FALSE(inputError([&] { readVolume(gz); }).empty());
    }
}

TEST_F(MalformedVolumes, MissingFilesFoldersAndUnknownExtensions) {
    EXPECT_NE(inputError([&] { readVolume(path("absent.nrrd")); }).find("absent.nrrd"),
              std::string::npos);
    std::filesystem::create_directories(path("folder.nii"));
    EXPECT_NE(inputError([&] { readVolume(path("folder.nii")); }).find("folder.nii"),
              std::string::npos);
    const auto other = writeFile("scan.mnc", "MINC");
    const std::string message = inputError([&] { readVolume(other); });
    EXPECT_NE(message.find("scan.mnc"), std::string::npos) << message;
    EXPECT_NE(message.find(".nrrd"), std::string::npos) << "should list what is supported";
    EXPECT_NE(message.find("DICOM"), std::string::npos) << "should list what is supported";
    // A .dcm name is DICOM's: one that is not a DICOM image says so.
    const auto dcm = writeFile("scan.dcm", "DICM");
    EXPECT_EQ(inputError([&] { readVolume(dcm); }), dcm.string() + ": not a DICOM image");
}

TEST_F(MalformedVolumes, OnlyRegularFilesAreReadAndTheMessageSaysWhatTheOthersAre) {
    std::filesystem::create_directories(path("folder.raw"));
    const NamedPipe pipe(path("pipe.raw"));
    ASSERT_TRUE(pipe.made());
    const std::string header = kGood + "data file: ";
    struct Named {
        std::string data;  // what the detached header names
        std::string shown; // the path its message shows
        std::string kind;
    };
    std::vector<Named> cases = {
        {"folder.raw", path("folder.raw").string(), "it is a folder, not a regular file"},
        {"pipe.raw", path("pipe.raw").string(), "it is a named pipe (FIFO), not a regular file"},
        {"none.raw", path("none.raw").string(), "no such file"},
    };
    if (std::filesystem::exists("/dev/zero"))
        cases.push_back({"/dev/zero", "/dev/zero", "it is a character device, not a regular file"});
    for (const Named& c : cases) {
        SCOPED_TRACE(c.data);
        const auto nhdr = writeFile("h.nhdr", header + c.data + "\n");
        EXPECT_EQ(inputError([&] { readVolume(nhdr); }), nhdr.string() + ": data file '" + c.data +
                                                             "' (" + c.shown +
                                                             "): cannot read it (" + c.kind + ")");
    }
    // The volume file itself, whatever its reader.
    for (const char* name : {"folder.nii", "pipe.nrrd"}) {
        SCOPED_TRACE(name);
        if (std::string(name) == "folder.nii") std::filesystem::create_directories(path(name));
        const NamedPipe other(path("pipe.nrrd"));
        const std::string kind = std::string(name) == "folder.nii"
                                     ? "it is a folder, not a regular file"
                                     : "it is a named pipe (FIFO), not a regular file";
        EXPECT_EQ(inputError([&] { readVolume(path(name)); }),
                  path(name).string() + ": cannot read volume (" + kind + ")");
        EXPECT_EQ(inputError([&] { readNrrd(path(name)); }),
                  path(name).string() + ": cannot read volume (" + kind + ")");
        EXPECT_EQ(inputError([&] { readNifti(path(name)); }),
                  path(name).string() + ": cannot read volume (" + kind + ")");
        EXPECT_FALSE(other.wasOpened());
    }
    EXPECT_FALSE(pipe.wasOpened()) << "a reader opened the pipe";
    // The control: a regular data file is read.
    writeFile("data.raw", std::string(64, '\x07'));
    EXPECT_EQ(readVolume(writeFile("h.nhdr", header + "data.raw\n")).value(0), 7.0);
}

} // namespace cutaway::test
