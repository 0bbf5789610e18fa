// Replays the fuzz targets' seed corpora (fuzz/corpus/) and every input that
// once made a fuzzer fail (fuzz/regressions/) through the same bodies the
// fuzzers run (fuzz/fuzz_entry.hpp), in the ordinary build and under
// `make test-sanitize`: each must end normally or in an InputError or
// RuntimeError, which the bodies expect.
#include "fuzz_entry.hpp"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <vector>

namespace cutaway::test {
namespace {

using Entry = void (*)(const std::uint8_t*, std::size_t);

const std::filesystem::path kFuzz = std::filesystem::path(CUTAWAY_SOURCE_DIR) / "fuzz";

/// The files of `folder` (none if it does not exist), sorted, README.md aside.
std::vector<std::filesystem::path> inputsIn(const std::filesystem::path& folder) {
    std::vector<std::filesystem::path> files;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
        if (entry.is_regular_file() && entry.path().filename() != "README.md")
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

/// Runs every input of fuzz/FOLDER/TARGET through `entry`; returns how many.
std::size_t replay(const std::string& folder, const std::string& target, Entry entry) {
    const auto files = inputsIn(kFuzz / folder / target);
    for (const auto& file : files) {
        std::ifstream in(file, std::ios::binary);
        const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
        try {
            entry(bytes.data(), bytes.size());
        } catch (const std::exception& e) {
            ADD_FAILURE() << file.string() << ": unexpected exception: " << e.what();
        }
    }
    return files.size();
}

} // namespace

TEST(FuzzReplay, SceneCorpus) {
    EXPECT_GE(replay("corpus", "scene", fuzz::fuzzScene), 50u);
}
TEST(FuzzReplay, NrrdCorpus) {
    EXPECT_GE(replay("corpus", "nrrd", fuzz::fuzzNrrd), 8u);
}
TEST(FuzzReplay, NiftiCorpus) {
    EXPECT_GE(replay("corpus", "nifti", fuzz::fuzzNifti), 8u);
}
TEST(FuzzReplay, MetaImageCorpus) {
    EXPECT_GE(replay("corpus", "metaimage", fuzz::fuzzMetaImage), 6u);
}
TEST(FuzzReplay, NhdrCorpus) {
    EXPECT_GE(replay("corpus", "nhdr", fuzz::fuzzNhdr), 6u);
}
TEST(FuzzReplay, GltfCorpus) {
    EXPECT_GE(replay("corpus", "gltf", fuzz::fuzzGltf), 2u);
}
TEST(FuzzReplay, DicomCorpus) {
    EXPECT_GE(replay("corpus", "dicom", fuzz::fuzzDicom), 7u);
}
// Each replay counts what it replayed: a missing or emptied folder fails.
TEST(FuzzReplay, SceneRegressions) {
    EXPECT_GE(replay("regressions", "scene", fuzz::fuzzScene), 10u);
}
TEST(FuzzReplay, NrrdRegressions) {
    EXPECT_GE(replay("regressions", "nrrd", fuzz::fuzzNrrd), 1u);
}
TEST(FuzzReplay, NiftiRegressions) {
    EXPECT_GE(replay("regressions", "nifti", fuzz::fuzzNifti), 1u);
}
TEST(FuzzReplay, MetaImageRegressions) {
    EXPECT_GE(replay("regressions", "metaimage", fuzz::fuzzMetaImage), 2u);
}
TEST(FuzzReplay, DicomRegressions) {
    EXPECT_GE(replay("regressions", "dicom", fuzz::fuzzDicom), 3u);
}
TEST(FuzzReplay, AMissingFolderReplaysNothing) {
    EXPECT_EQ(replay("regressions", "no-such-target", fuzz::fuzzScene), 0u)
        << "control: the counts above can fail";
}
TEST(FuzzReplay, NhdrRegressions) {
    EXPECT_GE(replay("regressions", "nhdr", fuzz::fuzzNhdr), 3u);
}
TEST(FuzzReplay, GltfRegressions) {
    EXPECT_GE(replay("regressions", "gltf", fuzz::fuzzGltf), 3u);
}

} // namespace cutaway::test
