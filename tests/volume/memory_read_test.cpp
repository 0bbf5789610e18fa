// readNrrdBytes and readNiftiBytes (the readers over bytes in memory, which
// the fuzz targets use) read what readNrrd and readNifti read from the same
// file, and fail with the same message, the file's name given as the name.
#include "volume_test_util.hpp"

#include <iterator>
#include <optional>

namespace cutaway::test {
namespace {

std::vector<std::byte> contentOf(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    // Appended, not sized up front: value-initializing zero bytes passes a
    // null pointer to memset, which UBSan reports.
    std::vector<std::byte> bytes;
    bytes.reserve(text.size());
    for (const char c : text)
        bytes.push_back(std::byte(c));
    return bytes;
}

template <typename FromFile, typename FromBytes>
void compareReaders(const std::vector<std::filesystem::path>& files, FromFile fromFile,
                    FromBytes fromBytes, bool allValid = false) {
    for (const auto& file : files) {
        SCOPED_TRACE(file.string());
        const auto bytes = contentOf(file);
        std::optional<Volume> expected;
        const std::string fileError = inputError([&] { expected = fromFile(file); });
        if (allValid) {
            ASSERT_TRUE(expected) << fileError;
        }
        std::optional<Volume> got;
        const std::string bytesError = inputError([&] { got = fromBytes(bytes, file.string()); });
        if (expected) {
            ASSERT_TRUE(got) << bytesError;
            expectSameVolume(*expected, *got);
        } else {
            EXPECT_EQ(fileError, bytesError);
        }
    }
}

} // namespace

using MemoryRead = VolumeFiles;

TEST_F(MemoryRead, NiftiBytesReadAsTheFile) {
    NiftiHeader h;
    h.dims[1] = 3;
    const std::string voxels = "abc";
    compareReaders(
        {writeFile("a.nii", h.bytes() + voxels), writeFile("a.nii.gz", gzip(h.bytes() + voxels)),
         writeFile("short.nii", h.bytes().substr(0, 100)),
         writeFile("truncated.nii.gz", gzip(h.bytes() + "ab")), writeFile("empty.nii", ""),
         writeFile("one.nii", "\x1f")},
        [](const auto& f) { return readNifti(f); },
        [](const auto& b, const std::string& n) { return readNiftiBytes(b, n); });
}

TEST_F(MemoryRead, NrrdBytesReadAsTheFile) {
    const std::string header = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 1 1\n";
    compareReaders(
        {writeFile("raw.nrrd", header + "encoding: raw\n\nab"),
         writeFile("gz.nrrd", header + "encoding: gzip\n\n" + gzip("ab")),
         writeFile("end.nrrd", header + "encoding: raw\nbyte skip: -1\n\nxyzab"),
         writeFile("skip.nrrd", header + "encoding: raw\nbyte skip: 1\nline skip: 1\n\nline\nxab"),
         writeFile("truncated.nrrd", header + "encoding: raw\n\na"),
         writeFile("past.nrrd", header + "encoding: raw\nbyte skip: 9\n\nab")},
        [](const auto& f) { return readNrrd(f); },
        [](const auto& b, const std::string& n) { return readNrrdBytes(b, n); });
}

TEST_F(MemoryRead, NrrdBytesCannotNameADataFile) {
    writeFile("data.raw", "ab");
    const auto file = writeFile("h.nhdr", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 1 1\n"
                                          "encoding: raw\ndata file: data.raw\n");
    EXPECT_EQ(readNrrd(file).voxelCount(), 2u);
    const std::string message = inputError([&] { readNrrdBytes(contentOf(file), "h.nhdr"); });
    EXPECT_NE(message.find("h.nhdr: data file 'data.raw' cannot be read"), std::string::npos)
        << message;
}

TEST(MemoryReadSeeds, FuzzSeedsReadAsTheirFiles) {
    // Every seed but the detached header is a valid file.
    const std::filesystem::path corpus = std::filesystem::path(CUTAWAY_SOURCE_DIR) / "fuzz/corpus";
    std::vector<std::filesystem::path> files[2];
    for (int f = 0; f < 2; ++f) {
        for (const auto& entry :
             std::filesystem::directory_iterator(corpus / (f ? "nifti" : "nrrd")))
            if (entry.path().extension() != ".nhdr") files[f].push_back(entry.path());
        ASSERT_GE(files[f].size(), 8u);
    }
    compareReaders(
        files[0], [](const auto& f) { return readNrrd(f); },
        [](const auto& b, const std::string& n) { return readNrrdBytes(b, n); }, true);
    compareReaders(
        files[1], [](const auto& f) { return readNifti(f); },
        [](const auto& b, const std::string& n) { return readNiftiBytes(b, n); }, true);
}

} // namespace cutaway::test
