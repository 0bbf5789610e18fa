// Several frames' files written at once: the default count, frames reported
// in order, and the same files as written one at a time.
#include "gpu_fixture.hpp"
#include "io/exr.hpp"
#include "job/render_job.hpp"
#include "job/sequence.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <vector>

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

std::string fileBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Renders an 8-frame turntable into `dir` with `writers` frames written at
// once; returns the frames in the order they were reported.
std::vector<int> renderTurntable(const gpu::Context& ctx, const fs::path& dir, int writers) {
    fs::remove_all(dir);
    Scene scene = parseScene(nlohmann::json::parse(R"({ "version": 1,
        "volume": { "phantom": "head", "size": [24, 24, 24] },
        "render": { "size": [64, 48] },
        "animation": { "frames": [0, 7], "tracks": [ { "target": "/camera/orbit/azimuth",
            "keys": [ { "frame": 0, "value": 0 }, { "frame": 8, "value": 360 } ] } ] },
        "output": { "pattern": "f_####.exr", "png": true } })"),
                             dir, "turn.json");
    job::SequenceOptions options;
    options.writers = writers;
    std::vector<int> reported;
    options.onFrame = [&](const job::FrameEvent& event) {
        EXPECT_EQ(event.kind, job::FrameEvent::Kind::Rendered) << event.error;
        reported.push_back(event.frame);
    };
    const job::SequenceSummary summary = job::renderSequence(ctx, scene, options);
    EXPECT_EQ(summary.rendered, 8);
    EXPECT_TRUE(std::is_sorted(summary.doneSeconds.begin(), summary.doneSeconds.end()));
    return reported;
}

} // namespace

TEST(WritesInFlight, OnePerCoreUpToEightWithinTheImagesBudget) {
    const std::size_t frame512 = 512 * 512 * 16; // RGBA floats
    EXPECT_EQ(job::writesInFlight(2, frame512), 2);
    EXPECT_EQ(job::writesInFlight(16, frame512), job::kMostWriters);
    EXPECT_EQ(job::writesInFlight(1, frame512), 1);
    EXPECT_EQ(job::writesInFlight(0, frame512), 1);              // the core count unknown
    EXPECT_EQ(job::writesInFlight(16, 3840 * 2160 * 16), 4);     // 4K: 127 MiB a frame
    EXPECT_EQ(job::writesInFlight(16, 7680 * 4320 * 16), 1);     // 8K: 506 MiB
    EXPECT_EQ(job::writesInFlight(16, std::size_t{1} << 31), 1); // past the budget: still one
    EXPECT_EQ(job::writesInFlight(16, 0), job::kMostWriters);
}

TEST_F(GpuTest, FramesWrittenAtOnceAreReportedInOrderAsTheSameFiles) {
    const fs::path base = fs::temp_directory_path() / "cutaway_sequence_writers";
    const std::vector<int> inOrder{0, 1, 2, 3, 4, 5, 6, 7};
    EXPECT_EQ(renderTurntable(ctx(), base / "one", 1), inOrder);
    EXPECT_EQ(renderTurntable(ctx(), base / "four", 4), inOrder);
    for (int f = 0; f < 8; ++f) {
        const std::string exr = job::expandPattern("f_####.exr", f);
        const std::string png = job::expandPattern("f_####.png", f);
        EXPECT_EQ(readExr(base / "four" / exr).rgba, readExr(base / "one" / exr).rgba) << exr;
        const std::string preview = fileBytes(base / "four" / png);
        EXPECT_FALSE(preview.empty()) << png;
        EXPECT_EQ(preview, fileBytes(base / "one" / png)) << png;
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(base / "four"), fs::directory_iterator{}), 16)
        << "a stray or missing file";
    fs::remove_all(base);
}

} // namespace cutaway::test
