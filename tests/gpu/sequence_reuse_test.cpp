// What does not change between frames is not redone: one upload and gradient
// bake per sequence, unless a track animates the volume itself.
#include "gpu_fixture.hpp"
#include "job/sequence.hpp"
#include "scene/scene.hpp"

#include <filesystem>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

job::SequenceSummary run(const gpu::Context& ctx, const std::string& tracks) {
    const auto dir = std::filesystem::temp_directory_path() / "cutaway_sequence_reuse";
    std::filesystem::remove_all(dir);
    Scene scene = parseScene(nlohmann::json::parse(R"({ "version": 1,
        "volume": { "phantom": "head", "size": [16, 16, 16] },
        "render": { "size": [16, 16] },
        "animation": { "frames": [0, 3], "tracks": [ )" +
                                                   tracks + R"( ] },
        "output": { "pattern": "f_####.exr" } })"),
                             dir, "reuse.json");
    job::SequenceSummary s = job::renderSequence(ctx, scene, {});
    std::filesystem::remove_all(dir);
    return s;
}

} // namespace

TEST_F(GpuTest, VolumeIsUploadedOncePerSequence) {
    const auto turn = run(ctx(), R"({ "target": "/camera/orbit/azimuth",
        "keys": [ { "frame": 0, "value": 0 }, { "frame": 4, "value": 360 } ] })");
    EXPECT_EQ(turn.rendered, 4);
    EXPECT_EQ(turn.volumeUploads, 1);
    const auto windowed = run(ctx(), R"({ "target": "/volume/window",
        "keys": [ { "frame": 0, "value": [0, 255] }, { "frame": 3, "value": [0, 120] } ] })");
    EXPECT_EQ(windowed.rendered, 4);
    EXPECT_EQ(windowed.volumeUploads, 4);
}

} // namespace cutaway::test
