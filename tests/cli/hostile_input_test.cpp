// Hostile volume files through `cutaway render`: each ends, within a time
// limit, in exit code 2 with a message naming the file (or the scene value
// at fault) and no output file. The readers' own tests
// (tests/volume/malformed_volumes_test.cpp) cover many more cases; these
// check the whole path, device included.
#include "cli_util.hpp"
#include "volume/volume_test_util.hpp"

#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

struct Hostile {
    std::string name;
    std::string content;
    std::string phrase; // in the message, besides the file's name
};

std::string nifti(void (*edit)(NiftiHeader&), std::size_t dataBytes = 64) {
    NiftiHeader h;
    h.dims[1] = h.dims[2] = h.dims[3] = 4;
    edit(h);
    return h.bytes() + std::string(dataBytes, '\x20');
}

const std::string kNrrd = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: ";

} // namespace

TEST_F(CliTest, HostileVolumeFilesExitTwoNamingThemAndWriteNothing) {
    const std::vector<Hostile> cases = {
        {"bomb.nrrd", kNrrd + "gzip\n\n" + gzip(std::string(64u << 20, '\0')),
         "exceeds the declared size"},
        {"truncated.nrrd", kNrrd + "raw\n\n" + std::string(100, '\x01'), "truncated"},
        {"absurd.nrrd",
         "NRRD0004\ntype: float\ndimension: 3\nsizes: 100000 100000 100000\nencoding: raw\n\n",
         "too large"},
        {"xml.nrrd", kNrrd + "xml\n\n", "unsupported encoding 'xml'"},
        {"offset.nii", nifti([](NiftiHeader& h) { h.voxOffset = 1e6f; }),
         "beyond the end of the file"},
        {"negative.nii", nifti([](NiftiHeader& h) { h.dims[2] = -4; }), "dim[2] is -4"},
        {"header-size.nii", nifti([](NiftiHeader& h) { h.sizeofHdr = 400; }), "sizeof_hdr"},
        {"datatype.nii", nifti([](NiftiHeader& h) { h.datatype = 1792; }), "datatype 1792"},
        // Valid, but a voxel 1e-30 mm thin across a 4 mm volume would need
        // 10^31 slicing planes: the frame never ended before.
        {"thin.nii", nifti([](NiftiHeader& h) { h.pixdim[1] = 1e-30f; }), "/render/slice_spacing"},
    };
    for (const Hostile& c : cases) {
        SCOPED_TRACE(c.name);
        fs::remove_all(m_dir / "frames");
        write(c.name, c.content);
        const fs::path scene = write("scene.json", R"({ "version": 1,
          "volume": { "file": ")" + c.name + R"(" }, "render": { "size": [16, 16] },
          "output": { "pattern": "frames/h_####.exr" } })");
        CommandResult r = runCutaway("render " + scene.string(), "timeout -k 5 120");
        EXPECT_EQ(r.code, 2) << r.output;
        const bool named = r.output.find(c.name) != std::string::npos ||
                           r.output.find("scene.json") != std::string::npos;
        EXPECT_TRUE(named) << r.output;
        EXPECT_NE(r.output.find(c.phrase), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(m_dir / "frames")) << "an output was written";
    }
}

} // namespace cutaway::test
