// The cutaway binary end to end: exit codes, messages, files written and not
// written. Every render runs with CUTAWAY_VALIDATION=1 and must print no
// validation message.
#include "cli_util.hpp"
#include "io/exr.hpp"
#include "volume/phantom.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

namespace fs = std::filesystem;

namespace {

using cutaway::test::CliTest;
using cutaway::test::CommandResult;
CommandResult run(const std::string& args) {
    return cutaway::test::runCutaway(args);
}

const char* kSmallScene = R"({
  "version": 1,
  "volume": { "phantom": "orange", "size": [32, 32, 32] },
  "camera": { "orbit": { "azimuth": 20, "elevation": 20 } },
  "render": { "size": [48, 40] },
  "output": { "pattern": "frames/orange_####.exr" }
})";

} // namespace

TEST_F(CliTest, RenderWritesExrAndPngAndNothingElse) {
    const fs::path scene = write("scene.json", kSmallScene);
    CommandResult r = run("render " + scene.string() + " --png");
    ASSERT_EQ(r.code, 0) << r.output;
    // Not a terminal: nothing but errors.
    EXPECT_TRUE(r.output.empty()) << r.output;
    EXPECT_EQ(files(m_dir / "frames"),
              (std::vector<std::string>{"orange_0000.exr", "orange_0000.png"}));
    cutaway::Image img = cutaway::readExr(m_dir / "frames" / "orange_0000.exr");
    EXPECT_EQ(img.width, 48);
    EXPECT_EQ(img.height, 40);
    EXPECT_FALSE(
        cutaway::readExrStringAttribute(m_dir / "frames" / "orange_0000.exr", "cutaway/scene")
            .empty());
}

TEST_F(CliTest, OutputAndSizeOverridesApply) {
    const fs::path scene = write("scene.json", kSmallScene);
    const fs::path out = m_dir / "other" / "x_%03d.exr";
    CommandResult r = run("render " + scene.string() + " -o " + out.string() + " --size 20x10 -q");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(r.output.empty()) << "--quiet must print nothing: " << r.output;
    cutaway::Image img = cutaway::readExr(m_dir / "other" / "x_000.exr");
    EXPECT_EQ(img.width, 20);
    EXPECT_EQ(img.height, 10);
}

TEST_F(CliTest, BadSceneExitsTwoNamingThePointerAndWritesNothing) {
    const fs::path scene = write("scene.json", R"({
      "version": 1, "volume": { "phantom": "orange", "size": [32, 32, 32] },
      "render": { "size": [48, -4], "slice_spacing": "fine" },
      "output": { "pattern": "frames/x_####.exr" } })");
    CommandResult r = run("render " + scene.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("/render/size/1"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("/render/slice_spacing"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames"));
}

TEST_F(CliTest, UsageErrorsExitTwo) {
    const fs::path scene = write("scene.json", kSmallScene);
    EXPECT_EQ(run("render " + scene.string() + " --size 0x5").code, 2);
    EXPECT_EQ(run("render " + scene.string() + " --size big").code, 2);
    EXPECT_EQ(run("render " + scene.string() + " --no-such-flag").code, 2);
    for (const char* writers : {"0", "33", "two"}) {
        CommandResult bad = run("render " + scene.string() + " --writers " + writers);
        EXPECT_EQ(bad.code, 2) << writers;
        EXPECT_NE(bad.output.find("--writers"), std::string::npos) << bad.output;
    }
    EXPECT_EQ(run("render").code, 2);
    EXPECT_EQ(run("").code, 2);
    CommandResult missing = run("render " + (m_dir / "absent.json").string());
    EXPECT_EQ(missing.code, 2);
    EXPECT_NE(missing.output.find("absent.json"), std::string::npos) << missing.output;
}

TEST_F(CliTest, HelpExitsZero) {
    for (const char* cmd : {"--help", "render --help", "validate --help", "info --help"}) {
        CommandResult r = run(cmd);
        EXPECT_EQ(r.code, 0) << cmd << ": " << r.output;
        EXPECT_NE(r.output.find("Usage"), std::string::npos) << cmd;
    }
}

// A voxel spacing beyond what renders (1e300 mm, 1e-12 mm), or one that puts
// more slicing planes across the volume than are drawn (1e-6 mm beside 1 mm),
// is refused by validate as by render, with the same message and exit 2
// (validate passed both); the control, nanometre voxels all round, passes.
TEST_F(CliTest, ValidateRefusesTheSpacingsRenderRefuses) {
    const std::string voxels(64, '\x40');
    for (const char* spacings : {"1e300 1 1", "1e-12 1 1", "1e-6 1 1", "1e-6 1e-6 1e-6"}) {
        const std::string spacing = spacings;
        SCOPED_TRACE(spacing);
        write("v.nrrd", std::string("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\n") +
                            "spacings: " + spacing + "\nencoding: raw\n\n" + voxels);
        const fs::path scene = write("s.json", R"({"version": 1, "volume": {"file": "v.nrrd"},
            "render": {"size": [16, 16]}, "output": {"pattern": "o_####.exr"}})");
        const CommandResult v = run("validate " + scene.string());
        const CommandResult r = run("render " + scene.string());
        const bool refused = spacing != "1e-6 1e-6 1e-6";
        EXPECT_EQ(v.code, refused ? 2 : 0) << v.output;
        EXPECT_EQ(r.code, refused ? 2 : 0) << r.output;
        if (!refused) continue;
        const std::string why =
            spacing == "1e-6 1 1" ? "planes across the" : " mm, outside the 1e-9 to 1e9 mm";
        for (const CommandResult* c : {&v, &r})
            EXPECT_NE(c->output.find(why), std::string::npos) << c->output;
        EXPECT_FALSE(fs::exists(m_dir / "o_0000.exr"));
    }
}

// A --device that names no device is a usage error (exit 2) listing them.
TEST_F(CliTest, UnknownDeviceIsAUsageErrorThatListsDevices) {
    const fs::path scene = write("scene.json", kSmallScene);
    CommandResult r = run("render " + scene.string() + " --device no-such-gpu");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--device \"no-such-gpu\" names no Vulkan device"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("name does not match"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames"));
}

TEST_F(CliTest, UnwritableOutputIsARuntimeErrorWithNoPartialFile) {
    const fs::path scene = write("scene.json", kSmallScene);
    write("blocker", "a file where a folder is expected");
    CommandResult r =
        run("render " + scene.string() + " -o " + (m_dir / "blocker" / "x.exr").string());
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("blocker"), std::string::npos) << r.output;
    EXPECT_EQ(files(m_dir), (std::vector<std::string>{"blocker", "scene.json"}));
}

TEST_F(CliTest, AMemoryBudgetTooSmallStopsTheRunNamingTheVolumeAndTheLimit) {
    const fs::path scene = write("scene.json", kSmallScene);
    CommandResult r = run("render " + scene.string() + " --memory-budget 64K --frames 0..3");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("the volume phantom orange (32x32x32) does not fit"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("memory budget of 64.0 KiB (--memory-budget)"), std::string::npos)
        << r.output;
    // The first frame's failure stops the run: the others would fail alike.
    EXPECT_NE(r.output.find("frame 0 failed"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("frame 1 failed"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames"));
    // Enough budget: the same scene renders.
    EXPECT_EQ(run("render " + scene.string() + " --memory-budget 64M").code, 0);

    CommandResult bad = run("render " + scene.string() + " --memory-budget 12Q");
    EXPECT_EQ(bad.code, 2) << bad.output;
    EXPECT_NE(bad.output.find("--memory-budget: expected a size such as 512M"), std::string::npos)
        << bad.output;
}

TEST_F(CliTest, AVolumePastTheDevicesMaxImageDimension3DIsRefusedNamingIt) {
    CommandResult devices = run("devices");
    ASSERT_EQ(devices.code, 0) << devices.output;
    const std::size_t at = devices.output.find("maxImageDimension3D ");
    ASSERT_NE(at, std::string::npos) << devices.output;
    const int limit = std::stoi(devices.output.substr(at + 20));
    const std::string wide = std::to_string(limit + 1);
    write("wide.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: " + wide +
                           " 2 2\nencoding: raw\n\n" + std::string((limit + 1) * 4, '\x40'));
    const fs::path scene = write("scene.json", R"({ "version": 1,
      "volume": { "file": "wide.nrrd" }, "render": { "size": [16, 16] },
      "output": { "pattern": "frames/w_####.exr" } })");
    CommandResult r = run("render " + scene.string());
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("wide.nrrd (" + wide + "x2x2) does not fit"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("maxImageDimension3D of " + std::to_string(limit)), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames"));
}

TEST_F(CliTest, ValidateChecksWithoutRendering) {
    const fs::path good = write("good.json", kSmallScene);
    CommandResult ok = run("validate " + good.string());
    EXPECT_EQ(ok.code, 0) << ok.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames"));
    const fs::path bad = write("bad.json", R"({ "version": 1, "volume": { "phantom": "pear" } })");
    CommandResult r = run("validate " + bad.string());
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("/volume/phantom"), std::string::npos) << r.output;
}

// validate refuses what render would refuse as bad input, frame by frame:
// operators that come to overlap in a later frame, a segment without voxels,
// output paths of the run its arguments describe.
TEST_F(CliTest, ValidateRefusesWhatRenderWould) {
    const fs::path moving = write("moving.json", R"({ "version": 1,
      "volume": { "phantom": "head", "size": [24, 24, 24] },
      "render": { "size": [24, 24] },
      "operators": [
        { "type": "retractor", "name": "left", "placement": { "translate": [-8, 0, 0], "scale": [6, 10, 10] } },
        { "type": "retractor", "name": "right", "placement": { "translate": [8, 0, 0], "scale": [6, 10, 10] } } ],
      "animation": { "frames": [0, 5], "tracks": [ { "target": "/operators/1/placement/translate",
        "keys": [ { "frame": 0, "value": [8, 0, 0] }, { "frame": 5, "value": [-4, 0, 0] } ] } ] },
      "output": { "pattern": "frames/m_####.exr" } })");
    CommandResult v = run("validate " + moving.string());
    EXPECT_EQ(v.code, 2) << v.output;
    EXPECT_NE(v.output.find("(frame 5): /operators/0 and /operators/1"), std::string::npos)
        << v.output;
    EXPECT_EQ(v.output.find("(frame 0)"), std::string::npos) << v.output;
    EXPECT_NE(v.output.find(" of 6 frames are not valid"), std::string::npos) << v.output;
    CommandResult early = run("validate " + moving.string() + " --frames 0..1");
    EXPECT_EQ(early.code, 0) << early.output;
    EXPECT_NE(early.output.find("valid (2 frame(s), 0..1)"), std::string::npos) << early.output;
    CommandResult r = run("render " + moving.string() + " --frames 5");
    EXPECT_EQ(r.code, 2) << "render agrees: " << r.output;

    // The run's output paths: one file for two frames, even one per shard.
    for (const std::string args :
         {" --frames 0..1 -o one.exr", " --frames 0..1 --shard 1/2 -o one.exr"}) {
        CommandResult o = run("validate " + moving.string() + args);
        EXPECT_EQ(o.code, 2) << args << o.output;
        EXPECT_NE(o.output.find("no frame number"), std::string::npos) << o.output;
    }

    const fs::path empty = write("empty.json", R"({ "version": 1,
      "volume": { "phantom": "head", "size": [24, 24, 24] },
      "labels": { "phantom": true },
      "operators": [ { "type": "peeler", "placement": { "scale": [10, 10, 10] },
                       "alignment": { "mode": "segment", "labels": [7] } } ] })");
    CommandResult e = run("validate " + empty.string());
    EXPECT_EQ(e.code, 2) << e.output;
    EXPECT_NE(e.output.find(empty.string() + " (frame 0): /operators/0/alignment:"),
              std::string::npos)
        << e.output;
    EXPECT_NE(e.output.find("segment of its alignment is empty"), std::string::npos) << e.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames"));
}

TEST_F(CliTest, InfoDescribesAVolume) {
    cutaway::Phantom p = cutaway::makePhantom("head", glm::ivec3(24, 20, 16), glm::dvec3(1, 1, 2));
    cutaway::writeNrrd(m_dir / "head.nrrd", p.values);
    CommandResult r = run("info " + (m_dir / "head.nrrd").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("24 x 20 x 16"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("uint8"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("1 x 1 x 2 mm"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("histogram"), std::string::npos) << r.output;
    CommandResult bad = run("info " + (m_dir / "nothing.nrrd").string());
    EXPECT_EQ(bad.code, 2);
    EXPECT_EQ(r.output.find("space"), std::string::npos) << "no placement given: " << r.output;
    // A placed volume: its space, origin and axes (j and k swapped here).
    cutaway::Volume placed = p.values;
    placed.space = cutaway::Space::LPS;
    placed.origin = {10, -20, 30};
    placed.direction = glm::dmat3(1, 0, 0, 0, 0, -1, 0, 1, 0);
    cutaway::writeNrrd(m_dir / "placed.nrrd", placed);
    CommandResult info = run("info " + (m_dir / "placed.nrrd").string());
    ASSERT_EQ(info.code, 0) << info.output;
    EXPECT_NE(info.output.find("space    LPS"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("origin   (10, -20, 30) mm"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("axis j   along (0, 0, -1)"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("axis k   along (0, 1, 0)"), std::string::npos) << info.output;
}

// `export` takes its folder and frame as `render` does: a missing folder is
// made, a bad frame number is named, a frame outside the animation warned of.
TEST_F(CliTest, ExportMakesItsFolderAndNamesABadFrame) {
    const fs::path scene = write("scene.json", kSmallScene);
    const fs::path out = m_dir / "new" / "deeper" / "x.nrrd";
    CommandResult r = run("export " + scene.string() + " -o " + out.string());
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::is_regular_file(out));
    CommandResult negative = run("export " + scene.string() + " --frame -1 -o " + out.string());
    EXPECT_EQ(negative.code, 2) << negative.output;
    EXPECT_NE(
        negative.output.find("--frame: expected one frame number in [0, 1000000], got \"-1\""),
        std::string::npos)
        << negative.output;
    CommandResult beyond = run("export " + scene.string() + " --frame 7 -o " + out.string());
    EXPECT_EQ(beyond.code, 0) << beyond.output;
    EXPECT_NE(beyond.output.find("warning: --frame reaches outside"), std::string::npos)
        << beyond.output;
}

// An operator whose box misses the volume renders (it is valid) but is
// warned of once, naming it; one inside the volume is not; -q is silent.
TEST_F(CliTest, AnOperatorOutsideTheVolumeIsWarnedOfOnce) {
    const std::string text = R"({ "version": 1,
      "volume": { "phantom": "orange", "size": [24, 24, 24] },
      "render": { "size": [24, 24] },
      "animation": { "frames": [0, 2] },
      "operators": [
        { "type": "dilator", "name": "lens", "placement": { "translate": [0, 0, 0], "scale": [6, 6, 6] } },
        { "type": "retractor", "name": "far away", "placement": { "translate": [500, 0, 0], "scale": [10, 10, 10] } } ],
      "output": { "pattern": "frames/o_####.exr" } })";
    const fs::path scene = write("scene.json", text);
    CommandResult r = run("render " + scene.string());
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string warning =
        "warning: " + scene.string() + ": /operators/1: \"far away\" lies outside the volume";
    EXPECT_NE(r.output.find(warning), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(warning), r.output.rfind(warning)) << "once, not per frame";
    EXPECT_EQ(r.output.find("/operators/0"), std::string::npos) << r.output;
    EXPECT_EQ(files(m_dir / "frames").size(), 3u);
    CommandResult quiet = run("render " + scene.string() + " -q");
    EXPECT_EQ(quiet.code, 0) << quiet.output;
    EXPECT_TRUE(quiet.output.empty()) << quiet.output;
    // validate gives the same warning, once, and still passes the scene.
    CommandResult v = run("validate " + scene.string());
    EXPECT_EQ(v.code, 0) << v.output;
    EXPECT_NE(v.output.find(warning), std::string::npos) << v.output;
    EXPECT_EQ(v.output.find(warning), v.output.rfind(warning)) << "once, not per frame";
    EXPECT_EQ(v.output.find("/operators/0"), std::string::npos) << v.output;
}
