// Meshes through the binary: a scene with a tool model renders; a broken
// model is bad input (exit 2) naming the file, from `validate` without a
// device and from `render` before any frame is written.
#include "cli_util.hpp"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

namespace fs = std::filesystem;

namespace cutaway::test {
namespace {

fs::path writeScene(const fs::path& dir, const std::string& meshFile) {
    fs::create_directories(dir);
    const fs::path scene = dir / "scene.json";
    std::ofstream(scene) << R"({"version": 1, "volume": {"phantom": "head", "size": [24, 24, 24]},
        "operators": [{"type": "retractor", "placement": {"scale": [12, 12, 12]}, "glyph": true}],
        "meshes": [{"file": ")"
                         << meshFile << R"(", "attach": 0,
                    "placement": {"translate": [0, -20, 0]}}],
        "output": {"pattern": "frames/f_####.exr"}})";
    return scene;
}

} // namespace

TEST_F(CliTest, ASceneWithAToolMeshRenders) {
    const fs::path model = fs::path(CUTAWAY_SOURCE_DIR) / "scenes/meshes/retractor.glb";
    const fs::path scene = writeScene(m_dir, model.string());
    const CommandResult v = runCutaway("validate " + scene.string());
    EXPECT_EQ(v.code, 0) << v.output;
    const CommandResult r = runCutaway("render " + scene.string() + " --size 32x32");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(m_dir / "frames/f_0000.exr"));
}

TEST_F(CliTest, ABrokenMeshIsBadInputNamingTheFile) {
    fs::create_directories(m_dir);
    std::ofstream(m_dir / "broken.glb") << "glTF but not really";
    const fs::path scene = writeScene(m_dir, "broken.glb");
    for (const char* command : {"validate ", "render "}) {
        const CommandResult r = runCutaway(command + scene.string());
        EXPECT_EQ(r.code, 2) << command << r.output;
        EXPECT_NE(r.output.find((m_dir / "broken.glb").string()), std::string::npos) << r.output;
    }
    EXPECT_FALSE(fs::exists(m_dir / "frames/f_0000.exr")) << "nothing may be written";
}

} // namespace cutaway::test
