// What does not change between frames is not redone: one upload and gradient
// bake per sequence, unless a track animates the volume itself.
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "job/sequence.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

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
    // Each rendered frame's completion, in order, within the run.
    ASSERT_EQ(turn.doneSeconds.size(), 4u);
    EXPECT_GT(turn.doneSeconds.front(), 0.0);
    EXPECT_TRUE(std::is_sorted(turn.doneSeconds.begin(), turn.doneSeconds.end()));
    EXPECT_LE(turn.doneSeconds.back(), turn.totalSeconds);
    const auto windowed = run(ctx(), R"({ "target": "/volume/window",
        "keys": [ { "frame": 0, "value": [0, 255] }, { "frame": 3, "value": [0, 120] } ] })");
    EXPECT_EQ(windowed.rendered, 4);
    EXPECT_EQ(windowed.volumeUploads, 4);
}

} // namespace cutaway::test

namespace cutaway::test {
namespace {

// A peeler over the 64^3 head phantom; `fields` are more of its members.
Scene peelerScene(const std::string& fields) {
    return parseScene(nlohmann::json::parse(R"({ "version": 1,
        "volume": { "phantom": "head", "size": [64, 64, 64] },
        "render": { "size": [32, 32] },
        "operators": [ { "type": "peeler",
          "placement": { "translate": [0, 0, 16], "scale": [32, 32, 16] }, )" +
                                            fields + R"( } ] })"),
                      std::filesystem::temp_directory_path(), "peeler.json");
}

Scene alignedScene(const std::string& alignment) {
    return peelerScene(R"("alignment": )" + alignment);
}

} // namespace

TEST_F(GpuTest, FeatureFieldsAreKeptWhileWantedAndFreedBeforeTheNextBakes) {
    const Scene surface = alignedScene(R"({ "mode": "surface", "depth": 4 })");
    const Scene segment = alignedScene(R"({ "mode": "segment", "range": [100, 255] })");
    VkDeviceSize segmentAlone = 0;
    {
        job::FrameRenderer fresh(ctx());
        ctx().resetMemoryPeak();
        fresh.render(segment);
        segmentAlone = ctx().memoryPeak();
    }
    job::FrameRenderer renderer(ctx());
    renderer.render(surface);
    EXPECT_EQ(renderer.takeNotes().size(), 1u) << "one field baked";
    renderer.render(surface);
    EXPECT_TRUE(renderer.takeNotes().empty()) << "the field is kept while wanted";
    // Switching alignment: the surface field (RGBA16F, 2 MiB at 64^3) is
    // freed before the segment mask bakes, so the peak is what the segment
    // frame needs alone.
    ctx().resetMemoryPeak();
    renderer.render(segment);
    EXPECT_EQ(renderer.takeNotes().size(), 1u);
    EXPECT_LT(ctx().memoryPeak(), segmentAlone + 64u * 64u * 64u * 8u / 2u)
        << "the old field was held during the bake";
}

// Repeated frames make the driver compile nothing new. lavapipe (Mesa 22.3)
// compiled the ray caster's operator shader again at every dispatch while the
// operators' uniforms sat in a uniform buffer (it inlines uniform values that
// steer branches) and kept every copy: about 1 MB a frame, and a compile.
// Counted as the process's executable mappings, where a CPU driver's code
// lives; without /proc there is nothing to count.
TEST_F(GpuTest, RepeatedFramesCompileNothingNew) {
    const auto codeMappings = [] {
        std::ifstream maps("/proc/self/maps");
        int n = 0;
        for (std::string line; std::getline(maps, line);)
            n += line.find(" r-xp ") != std::string::npos;
        return n;
    };
    if (codeMappings() == 0) GTEST_SKIP() << "no /proc/self/maps";
    for (RenderMethod method : {RenderMethod::Raycast, RenderMethod::Slicing}) {
        Scene scene = alignedScene(R"({ "mode": "surface", "depth": 4 })");
        scene.render.method = method;
        job::FrameRenderer renderer(ctx());
        for (int i = 0; i < 2; ++i) // the pipelines are made, the field baked
            renderer.render(scene);
        const int before = codeMappings();
        for (int i = 0; i < 6; ++i) {
            scene.camera.azimuthDeg += 10.0;
            renderer.render(scene);
        }
        EXPECT_EQ(codeMappings(), before)
            << (method == RenderMethod::Raycast ? "raycast" : "slicing");
    }
    // An animated peeler: its map baked again at every frame.
    const auto peeledBy = [](int angle) {
        Scene scene = peelerScene(R"("params": { "angle": )" + std::to_string(angle) + " }");
        scene.render.method = RenderMethod::Raycast;
        return scene;
    };
    job::FrameRenderer renderer(ctx());
    for (int angle : {30, 40})
        renderer.render(peeledBy(angle));
    const int before = codeMappings();
    for (int angle = 50; angle < 110; angle += 10)
        renderer.render(peeledBy(angle));
    EXPECT_EQ(codeMappings(), before) << "an animated operator";
}

} // namespace cutaway::test
