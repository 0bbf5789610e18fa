// Same scene, same machine: byte-identical files, whichever process writes a
// frame. A surface-aligned operator's distance field is baked by the first
// frame of each process; its header notes must not say when or how long.
#include "cli_util.hpp"
#include "io/exr.hpp"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>

namespace fs = std::filesystem;

namespace cutaway::test {
namespace {

std::string bytesOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// Four frames of a small head phantom turning under a surface-aligned peeler.
const char* kPeeledTurntable = R"({ "version": 1,
  "volume": { "phantom": "head", "size": [48, 48, 48] },
  "camera": { "orbit": { "elevation": 40 } },
  "render": { "size": [48, 48] },
  "operators": [{ "type": "peeler", "name": "scalp flap",
    "placement": { "translate": [0, 0, 16], "scale": [34, 34, 12] },
    "alignment": { "mode": "surface", "threshold": "otsu", "depth": 2, "band": 1 },
    "params": { "thickness": 10, "radius": 3, "angle": 150, "width": 22 } }],
  "animation": { "frames": [0, 3], "tracks": [{ "target": "/camera/orbit/azimuth",
    "keys": [{ "frame": 0, "value": 0 }, { "frame": 4, "value": 360 }] }] } })";

} // namespace

TEST_F(CliTest, OneProcessAndTwoShardsWriteTheSameBytes) {
    const fs::path scene = write("peeled.json", kPeeledTurntable);
    const auto render = [&](const std::string& folder, const std::string& options) {
        CommandResult r = runCutaway("render " + scene.string() + " -o " +
                                     (m_dir / folder / "f_####.exr").string() + " " + options);
        ASSERT_EQ(r.code, 0) << r.output;
    };
    render("whole", "");
    render("shards", "--shard 0/2");
    render("shards", "--shard 1/2");
    render("again", "--frames 2..3"); // a rerun starting elsewhere
    const std::vector<std::string> names = files(m_dir / "whole");
    ASSERT_EQ(names.size(), 4u);
    EXPECT_EQ(files(m_dir / "shards"), names);
    for (const std::string& name : names) {
        SCOPED_TRACE(name);
        const std::string whole = bytesOf(m_dir / "whole" / name);
        EXPECT_TRUE(bytesOf(m_dir / "shards" / name) == whole) << "a shard wrote other bytes";
        if (fs::exists(m_dir / "again" / name)) {
            EXPECT_TRUE(bytesOf(m_dir / "again" / name) == whole) << "a rerun wrote other bytes";
        }
        // Every frame records the field it used, and nothing of time.
        const std::string note = readExrStringAttribute(m_dir / "whole" / name, "cutaway/note0");
        EXPECT_EQ(note.rfind("scalp flap: distance field of the object above ", 0), 0u) << note;
        EXPECT_EQ(note.find("baked"), std::string::npos) << note;
        EXPECT_EQ(note, readExrStringAttribute(m_dir / "whole" / names[0], "cutaway/note0"));
    }
    // The control: the frames differ from each other (the view turns).
    EXPECT_TRUE(bytesOf(m_dir / "whole" / names[0]) != bytesOf(m_dir / "whole" / names[1]));
}

} // namespace cutaway::test
