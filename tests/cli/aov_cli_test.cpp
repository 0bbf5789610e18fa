// The EXR channels beyond colour, as compositors read them: `cutaway render`
// with /output/aovs and /output/mattes writes "Z", "label", "operator_id" and
// "matte.<label>" as FLOAT channels (also beside half colour), which OpenEXR's
// own exrheader and OpenImageIO's oiiotool (Debian's openexr and
// openimageio-tools, installed by scripts/install-deps.sh) list and read.
#include "cli_util.hpp"
#include "core/error.hpp"
#include "io/exr.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>

namespace cutaway::test {
namespace fs = std::filesystem;

namespace {

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

constexpr const char* kScene = R"({ "version": 1,
  "volume": { "phantom": "head", "size": [32, 32, 32] },
  "labels": { "phantom": true },
  "transfer": { "points": [ { "value": 50, "color": [0.9, 0.7, 0.6], "alpha": 0 },
                            { "value": 200, "color": [1, 1, 0.9], "alpha": 0.9 } ] },
  "render": { "size": [24, 20], "background": "transparent" },
  "output": { "pattern": "f_####.exr", "aovs": ["Z", "label", "operator_id"],
              "mattes": ["skin", 3] } })";

} // namespace

TEST_F(CliTest, CompositingChannelsAreReadByOpenExrAndOpenImageIo) {
    const fs::path scene = write("aov.json", kScene);
    const CommandResult r = runCutaway("render " + scene.string());
    ASSERT_EQ(r.code, 0) << r.output;
    const fs::path exr = m_dir / "f_0000.exr";

    const CommandResult header = runProgram("exrheader", exr.string());
    ASSERT_EQ(header.code, 0) << "exrheader (Debian's openexr) must be installed: "
                              << header.output;
    for (const char* line :
         {"Z, 32-bit floating-point", "label, 32-bit floating-point",
          "operator_id, 32-bit floating-point", "matte.skin, 32-bit floating-point",
          "matte.3, 32-bit floating-point", "R, 16-bit floating-point"})
        EXPECT_TRUE(has(header.output, line)) << line << " in\n" << header.output;

    const CommandResult info = runProgram("oiiotool", "--info -v " + exr.string());
    ASSERT_EQ(info.code, 0) << "oiiotool (Debian's openimageio-tools) must be installed: "
                            << info.output;
    EXPECT_TRUE(has(info.output, "24 x   20, 9 channel")) << info.output;
    // OpenImageIO knows Z as the depth channel; the others keep their names.
    for (const char* name : {"Z (float)", "label (float)", "operator_id (float)",
                             "matte.skin (float)", "matte.3 (float)"})
        EXPECT_TRUE(has(info.output, name)) << name << " in\n" << info.output;

    // oiiotool reads the values: no NaN anywhere, Z infinite where nothing
    // is visible (the corners) and nowhere else.
    const CommandResult stats =
        runProgram("oiiotool", exr.string() + " --ch Z,label,matte.3 --printstats");
    ASSERT_EQ(stats.code, 0) << stats.output;
    EXPECT_TRUE(has(stats.output, "Stats NanCount: 0 0 0")) << stats.output;

    const auto z = readExrChannel(exr, "Z");
    const auto label = readExrChannel(exr, "label");
    const auto brain = readExrChannel(exr, "matte.3");
    ASSERT_EQ(z.size(), 24u * 20u);
    int finite = 0;
    for (std::size_t p = 0; p < z.size(); ++p) {
        if (!std::isfinite(z[p])) {
            EXPECT_EQ(label[p], 0.0f) << "nothing visible at " << p;
        }
        EXPECT_TRUE(label[p] >= 0.0f && label[p] <= 3.0f) << label[p];
        finite += std::isfinite(z[p]);
    }
    EXPECT_GT(finite, 30);
    EXPECT_LT(finite, int(z.size()));
    EXPECT_TRUE(has(stats.output, "Stats InfCount: " + std::to_string(z.size() - finite) + " 0 0"))
        << stats.output;
    EXPECT_GT(*std::max_element(brain.begin(), brain.end()), 0.0f);
}

TEST_F(CliTest, CompositingChannelsAreRefusedWithTheirPointer) {
    const fs::path scene = write("aov.json", kScene);
    CommandResult r = runCutaway("render " + scene.string() + " --set /labels=null");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_TRUE(has(r.output, "/output/aovs/1")) << r.output;
    EXPECT_TRUE(has(r.output, "/output/mattes")) << r.output;
    r = runCutaway("render " + scene.string() + " --set '/output/aovs=[\"depth\"]'");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_TRUE(has(r.output, "/output/aovs/0")) << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "f_0000.exr")) << "nothing is written";
}

} // namespace cutaway::test
