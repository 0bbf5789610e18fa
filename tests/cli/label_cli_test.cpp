// Labels through the binary: a listed label that no voxel carries is warned
// of, by `validate` and by `render`, and the run still succeeds.
#include "cli_util.hpp"

#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

std::string sceneListing(const std::string& labels) {
    const std::string points = R"([{"value": 0, "color": [1, 1, 1], "alpha": 0},
                                   {"value": 255, "color": [1, 1, 1], "alpha": 1}])";
    return R"({"version": 1, "volume": {"phantom": "head", "size": [16, 16, 16]},
               "labels": {"phantom": true}, "render": {"size": [16, 16]},
               "transfer": {"points": )" +
           points + R"(, "labels": [{"labels": )" + labels + R"(, "points": )" + points + "}]}}";
}

TEST_F(CliTest, ALabelNoVoxelCarriesIsWarnedOf) {
    const auto scene = write("s.json", sceneListing(R"(["skull", 77])"));
    for (const std::string& command :
         {"validate " + scene.string(),
          "render " + scene.string() + " -o " + (m_dir / "f_#.exr").string()}) {
        SCOPED_TRACE(command);
        const CommandResult r = runCutaway(command);
        EXPECT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("warning: " + scene.string() +
                                ": /transfer/labels/0/labels: label 77 is carried by no voxel"),
                  std::string::npos)
            << r.output;
        EXPECT_EQ(r.output.find("label 2 "), std::string::npos) << r.output;
    }
    // Control: every listed label is there, no warning.
    const CommandResult clean =
        runCutaway("validate " + write("t.json", sceneListing(R"(["skull"])")).string());
    EXPECT_EQ(clean.output.find("warning"), std::string::npos) << clean.output;
}

} // namespace
} // namespace cutaway::test
