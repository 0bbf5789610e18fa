// Hostile volume files through `cutaway render`: each ends, within a time
// limit, in exit code 2 with a message naming the file (or the scene value
// at fault) and no output file. The readers' own tests
// (tests/volume/malformed_volumes_test.cpp) cover many more cases; these
// check the whole path, device included.
#include "cli_util.hpp"
#include "io/exr.hpp"
#include "volume/volume_test_util.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <gtest/gtest.h>
#include <limits>
#include <map>
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
        // A voxel 1e-30 mm thin across a 4 mm volume would need 10^31
        // slicing planes (the frame never ended once): below what renders.
        {"thin.nii", nifti([](NiftiHeader& h) { h.pixdim[1] = 1e-30f; }),
         "outside the 1e-9 to 1e9 mm"},
        // Within that range, but 1e-8 mm beside 1 mm: more planes than drawn.
        {"thin-planes.nii", nifti([](NiftiHeader& h) { h.pixdim[1] = 1e-8f; }),
         "/render/slice_spacing"},
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

namespace {

// A float NRRD of 16^3 voxels: 100 in a ball, 0 around it, with `edit` applied.
std::string ballNrrd(void (*edit)(std::vector<float>&)) {
    std::vector<float> values(16 * 16 * 16);
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                const double r = std::hypot(x - 7.5, y - 7.5, z - 7.5);
                values[static_cast<std::size_t>(x + 16 * (y + 16 * z))] = r < 6.0 ? 100.0f : 0.0f;
            }
    edit(values);
    std::string bytes(values.size() * sizeof(float), '\0');
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return "NRRD0004\ntype: float\ndimension: 3\nsizes: 16 16 16\nendian: little\n"
           "encoding: raw\n\n" +
           bytes;
}

} // namespace

TEST_F(CliTest, NonFiniteVoxelsAreLeftOutOfTheWindowAndRenderedAsEmpty) {
    write("inf.nrrd", ballNrrd([](std::vector<float>& v) {
              v[0] = std::numeric_limits<float>::infinity();
              v[100] = -std::numeric_limits<float>::infinity();
          }));
    write("nan.nrrd",
          ballNrrd([](std::vector<float>& v) { v[5] = std::numeric_limits<float>::quiet_NaN(); }));
    // The control: the same voxels empty (the smallest value).
    write("empty.nrrd", ballNrrd([](std::vector<float>& v) { v[0] = v[5] = v[100] = 0.0f; }));
    write("all-nan.nrrd", ballNrrd([](std::vector<float>& v) {
              v.assign(v.size(), std::numeric_limits<float>::quiet_NaN());
          }));
    std::map<std::string, Image> images;
    for (const char* name : {"inf", "nan", "empty", "all-nan"}) {
        const fs::path scene = write(std::string(name) + ".json", R"({ "version": 1,
          "volume": { "file": ")" + std::string(name) + R"(.nrrd" },
          "render": { "size": [32, 32] }, "output": { "pattern": ")" + name +
                                                                      R"(.exr" } })");
        CommandResult r = runCutaway("render " + scene.string());
        EXPECT_EQ(r.code, 0) << name << ": " << r.output;
        const std::string count = std::string(name) == "inf"     ? "2 voxels are not finite"
                                  : std::string(name) == "nan"   ? "1 voxel is not finite"
                                  : std::string(name) == "empty" ? ""
                                                                 : "all 4096 voxels are not finite";
        if (!count.empty()) {
            EXPECT_NE(r.output.find("warning: " + scene.string() + ": /volume/file: " +
                                    (m_dir / (std::string(name) + ".nrrd")).string() + ": " +
                                    count),
                      std::string::npos)
                << r.output;
        }
        images[name] = readExr(m_dir / (std::string(name) + ".exr"));
    }
    // One infinite voxel made the window [0, inf]: the whole image blank.
    EXPECT_EQ(images["inf"].rgba, images["empty"].rgba);
    EXPECT_EQ(images["nan"].rgba, images["empty"].rgba);
    float alpha = 0.0f;
    for (std::size_t i = 3; i < images["empty"].rgba.size(); i += 4)
        alpha = std::max(alpha, images["empty"].rgba[i]);
    EXPECT_GT(alpha, 0.5f) << "the ball is visible";
    // validate and export warn alike; info counts them.
    CommandResult v = runCutaway("validate " + (m_dir / "inf.json").string());
    EXPECT_EQ(v.code, 0) << v.output;
    EXPECT_NE(v.output.find("2 voxels are not finite"), std::string::npos) << v.output;
    CommandResult e = runCutaway("export " + (m_dir / "inf.json").string() + " -o " +
                                 (m_dir / "x.nrrd").string());
    EXPECT_EQ(e.code, 0) << e.output;
    EXPECT_NE(e.output.find("2 voxels are not finite"), std::string::npos) << e.output;
    CommandResult info = runCutaway("info " + (m_dir / "inf.nrrd").string());
    EXPECT_NE(info.output.find("values   [0, 100]"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("non-finite 2 voxel(s)"), std::string::npos) << info.output;
}

} // namespace cutaway::test
