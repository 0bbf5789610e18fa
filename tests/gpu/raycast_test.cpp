// render.method "raycast" against slicing: the ray caster takes its samples
// where the slicing planes cross each ray and calls the same per-sample code,
// so, taking every sample, the two images agree to float rounding (each
// stops a pixel at its own point past render.termination_opacity; that is
// checked on its own). Checked for both classifications, both projections,
// classification by label, lights and a transparent background.
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

namespace cutaway::test {
namespace {

using nlohmann::json;

json headScene() {
    return {
        {"version", 1},
        {"volume", {{"phantom", "head"}, {"size", {64, 64, 64}}}},
        {"labels", {{"phantom", true}}},
        {"transfer", json::parse(R"({"points": [{"value": 0, "color": [0.9, 0.7, 0.6], "alpha": 0},
              {"value": 60, "color": [0.9, 0.7, 0.6], "alpha": 0.05},
              {"value": 200, "color": [1, 1, 0.9], "alpha": 0.8}]})")},
        {"camera", {{"orbit", {{"azimuth", 30}, {"elevation", 20}, {"distance", 220}}}}},
        // Every sample: each method stops a pixel at its own point past the
        // termination opacity (see Raycast.StopsWhereTheSceneSays).
        {"render",
         {{"size", {80, 72}}, {"background", "transparent"}, {"termination_opacity", 1.0}}},
    };
}

Image render(const gpu::Context& ctx, json document, const char* method) {
    document["render"]["method"] = method;
    return job::renderImage(ctx, parseScene(document, "/nonexistent", "test"));
}

class Raycast : public GpuTest {
protected:
    // Renders `scene` both ways and checks they agree; returns the coverage.
    double expectSameAsSlicing(const json& scene, const std::string& what) {
        const Image sliced = render(ctx(), scene, "slicing");
        const Image cast = render(ctx(), scene, "raycast");
        expectAgree(sliced, cast, kTolerance, what);
        double coverage = 0.0;
        for (std::size_t i = 3; i < cast.rgba.size(); i += 4)
            coverage += cast.rgba[i];
        return coverage;
    }
    // Rounding of the sample points, computed two ways (measured on lavapipe:
    // up to 2.4e-3 in one pixel of the 72 x 101 picture).
    static constexpr float kTolerance = 4e-3f;
};

TEST_F(Raycast, MatchesSlicingPreintegratedAndPost) {
    json scene = headScene();
    EXPECT_GT(expectSameAsSlicing(scene, "pre-integrated"), 500.0) << "the head must be visible";
    scene["render"]["classification"] = "post";
    expectSameAsSlicing(scene, "post-classified");
    scene["render"]["slice_spacing"] = 0.5;
    expectSameAsSlicing(scene, "post-classified, d = 0.5");
    // 13 rows of 8x8 tiles, the last partial, taken in shared/tile_order.h's order.
    scene["render"]["size"] = {72, 101};
    expectSameAsSlicing(scene, "72x101");
}

TEST_F(Raycast, TransparentRunsAskOnlyWhetherASlabCanShow) {
    // While nothing shows the rays ask only which values can (mayShow), then
    // read the whole table texel: colours without red (or green, or blue)
    // must show all the same, in both classifications.
    json scene = headScene();
    scene.erase("labels");
    scene["transfer"] = json::parse(R"({"points": [{"value": 0, "color": [0, 0.6, 1], "alpha": 0},
          {"value": 60, "color": [0, 0.6, 1], "alpha": 0.05},
          {"value": 140, "color": [1, 0, 0.5], "alpha": 0.3},
          {"value": 200, "color": [0.4, 1, 0], "alpha": 0.8}]})");
    EXPECT_GT(expectSameAsSlicing(scene, "pre-integrated, colours without a channel"), 500.0);
    scene["render"]["classification"] = "post";
    EXPECT_GT(expectSameAsSlicing(scene, "post-classified, colours without a channel"), 500.0);
}

// render.termination_opacity: a pixel takes no more samples once its opacity
// reaches it, in both methods. Against the same method taking every sample,
// what is missing is less than 1 minus it; pixels that never reach it are
// the same; and rays do stop early (pixels lack more than a quarter of what
// they may). The default is 1 - 1/255: at most one step of an 8-bit image.
TEST_F(Raycast, StopsWhereTheSceneSays) {
    for (const char* method : {"slicing", "raycast"}) {
        json scene = headScene();
        const Image every = render(ctx(), scene, method);
        for (const double cutoff : {0.9, kDefaultTerminationOpacity}) {
            scene["render"]["termination_opacity"] = cutoff;
            const Image stopped = render(ctx(), scene, method);
            const std::string what = std::string(method) + " at " + std::to_string(cutoff);
            const float lack = float(1.0 - cutoff);
            std::size_t stoppedEarly = 0, wrong = 0;
            for (std::size_t i = 0; i < every.rgba.size(); i += 4) {
                const float missing = every.rgba[i + 3] - stopped.rgba[i + 3];
                float worst = 0.0f;
                for (std::size_t c = 0; c < 3; ++c)
                    worst = std::max(worst, std::abs(every.rgba[i + c] - stopped.rgba[i + c]));
                // Lit colours may reach ~1.3 of the transfer function's.
                const bool bounded =
                    missing >= -1e-5f && missing <= lack + 1e-5f && worst <= 1.5f * lack + 1e-5f;
                const bool untouched =
                    stopped.rgba[i + 3] >= float(cutoff) || (missing == 0.0f && worst == 0.0f);
                wrong += !(bounded && untouched);
                stoppedEarly += missing > 0.25f * lack;
            }
            EXPECT_EQ(wrong, 0u) << what;
            // Measured: 241 and 733 pixels at 0.9, 22 and 667 at the default
            // (slicing stops after a chunk of slices, past the opacity).
            EXPECT_GT(stoppedEarly, 10u) << what << ": the setting must stop rays";
        }
    }
}

TEST_F(Raycast, MatchesSlicingOrthographicWithLightsAndLabels) {
    json scene = headScene();
    scene["camera"]["projection"] = "orthographic";
    scene["lights"] = {{"ambient", 0.1},
                       {"headlight", 0.5},
                       {"directional", {{{"direction", {1, -1, -1}}, {"intensity", 0.7}}}}};
    scene["transfer"]["labels"] =
        json::array({{{"labels", {"brain"}},
                      {"points", json::parse(R"([{"value": 0, "color": [0.9, 0.5, 0.5], "alpha": 0},
              {"value": 135, "color": [1.0, 0.8, 0.8], "alpha": 0.9}])")}}});
    EXPECT_GT(expectSameAsSlicing(scene, "orthographic, lights, labels"), 500.0);
}

// A scan that is air but for a spherical shell (value 200) and a ball (100),
// placed off centre so that a cell grid read mirrored skips visible samples.
// Its sizes are not multiples of a cell (4) or a brick (8).
Volume shellAndBall() {
    Volume v = Volume::allocate({61, 70, 45}, VoxelType::U8);
    for (int z = 0; z < v.dims.z; ++z)
        for (int y = 0; y < v.dims.y; ++y)
            for (int x = 0; x < v.dims.x; ++x) {
                const double shell = glm::length(glm::dvec3(x, y, z) - glm::dvec3(22, 44, 24));
                const double ball = glm::length(glm::dvec3(x, y, z) - glm::dvec3(47, 14, 12));
                // Edges ramp over two voxels: sharp ones make the two methods'
                // rounding of the sample points show.
                const double inShell = std::clamp(2.5 - std::abs(shell - 15.5), 0.0, 1.0);
                const double inBall = std::clamp(6.0 - ball, 0.0, 1.0);
                v.data[v.index(x, y, z)] =
                    std::byte(static_cast<uint8_t>(std::max(200.0 * inShell, 100.0 * inBall)));
            }
    return v;
}

class RaycastCells : public Raycast {
protected:
    void SetUp() override {
        Raycast::SetUp();
        writeNrrd(m_file, shellAndBall());
    }
    void TearDown() override {
        std::filesystem::remove(m_file);
        Raycast::TearDown();
    }
    json sceneWith(const char* transfer) const {
        json scene = headScene();
        scene["volume"] = {{"file", m_file.string()}};
        scene.erase("labels");
        scene["transfer"] = json::parse(transfer);
        return scene;
    }
    const std::filesystem::path m_file =
        std::filesystem::temp_directory_path() /
        ("cutaway_raycast_cells_" + std::to_string(::getpid()) + ".nrrd");
};

// Shell and ball.
constexpr const char* kBoth = R"({"points": [{"value": 0, "color": [1, 1, 1], "alpha": 0},
    {"value": 60, "color": [1, 1, 1], "alpha": 0},
    {"value": 200, "color": [1, 0.9, 0.8], "alpha": 0.5}]})";
// The shell only: the ball's cells are empty.
constexpr const char* kShellOnly = R"({"points": [{"value": 0, "color": [1, 1, 1], "alpha": 0},
    {"value": 150, "color": [1, 1, 1], "alpha": 0},
    {"value": 200, "color": [1, 0.9, 0.8], "alpha": 0.5}]})";
// The ball only: the shell's cells are empty.
constexpr const char* kBallOnly = R"({"points": [{"value": 0, "color": [1, 1, 1], "alpha": 0},
    {"value": 60, "color": [1, 0.5, 0.5], "alpha": 0},
    {"value": 100, "color": [1, 0.5, 0.5], "alpha": 0.4},
    {"value": 140, "color": [1, 0.5, 0.5], "alpha": 0}]})";

TEST_F(RaycastCells, StepsOverEmptyCellsWithoutLosingASample) {
    // The rays cross the shell's front, step over the empty cells inside it
    // and around it, and meet its back and the ball; the close camera makes
    // them cross cells at every angle.
    json scene = sceneWith(kBoth);
    scene["camera"]["orbit"]["distance"] = 130;
    EXPECT_GT(expectSameAsSlicing(scene, "pre-integrated"), 300.0) << "the shell must show";
    scene["render"]["classification"] = "post";
    scene["camera"]["orbit"]["azimuth"] = 117;
    scene["camera"]["orbit"]["elevation"] = -35;
    expectSameAsSlicing(scene, "post-classified, another view");
    // Longer slabs, and more oblique rays at the corners: the cells' margin
    // grows with them.
    scene["render"]["classification"] = "preintegrated";
    scene["render"]["slice_spacing"] = 2.5;
    scene["camera"]["fov"] = 70;
    expectSameAsSlicing(scene, "d = 2.5, a wide field of view");
}

TEST_F(RaycastCells, FollowTheTransferFunctionFromFrameToFrame) {
    // One renderer, frames that switch between the shell only and the ball
    // only, and a longer slab (a wider margin for the kept value spans):
    // cells or bricks kept from an earlier frame would step over what shows,
    // or spans kept for another margin would miss a slab's far end. Each frame
    // must equal a fresh renderer's.
    for (const char* method : {"raycast", "slicing"}) {
        job::FrameRenderer renderer(ctx());
        Image previous;
        int frame = 0;
        for (const auto& [transfer, spacing] :
             {std::pair{kShellOnly, 1.0}, {kBallOnly, 1.0}, {kBallOnly, 2.5}, {kShellOnly, 2.5}}) {
            json document = sceneWith(transfer);
            document["render"]["method"] = method;
            document["render"]["slice_spacing"] = spacing;
            const Scene scene = parseScene(document, "/nonexistent", "test");
            const Image fresh = job::renderImage(ctx(), scene);
            const Image reused = renderer.render(scene);
            EXPECT_LT(compareImages(reused, fresh).maxAbs, 1e-6f) << method << " frame " << frame;
            if (frame > 0) {
                EXPECT_GT(compareImages(previous, reused).maxAbs, 0.05f)
                    << method << " frame " << frame << " must differ from the one before";
            }
            previous = reused;
            ++frame;
        }
    }
}

TEST_F(Raycast, FramesHoldNoSlicingTargets) {
    // A ray-cast frame writes its own storage image: slicing's colour target
    // and its read-back buffer (and depth-stencil) come with the first sliced
    // frame, not before. 24 MiB of a ray-cast frog_labels render.
    json scene = headScene();
    scene["render"]["size"] = {256, 256};
    job::FrameRenderer renderer(ctx());
    scene["render"]["method"] = "raycast";
    renderer.render(parseScene(scene, "/nonexistent", "test"));
    const VkDeviceSize cast = ctx().memoryInUse();
    scene["render"]["method"] = "slicing";
    renderer.render(parseScene(scene, "/nonexistent", "test"));
    const VkDeviceSize sliced = ctx().memoryInUse();
    const VkDeviceSize colour = 256 * 256 * 8; // RGBA16F at least
    EXPECT_GE(sliced, cast + 2 * colour) << "ray cast " << cast << ", then sliced " << sliced;
}

TEST_F(Raycast, TheToleranceSeesADifferentStep) {
    // The comparisons above can fail: samples 2 planes apart instead of 1
    // differ from slicing by far more than the tolerance, on any device
    // (expectAgree). Whole slabs: refined ones (the default) come so close
    // to the converged picture that the spacing shows less (rms 3.8e-3).
    json scene = headScene();
    scene["render"]["refine"] = 1;
    const Image sliced = render(ctx(), scene, "slicing");
    scene["render"]["slice_spacing"] = 2.0;
    const Image coarser = render(ctx(), scene, "raycast");
    const ImageDiff d = compareImages(sliced, coarser);
    EXPECT_GT(d.maxAbs, 10.0f * kTolerance);
    EXPECT_GT(d.rms, 2.0 * kQuantizedRms);
}

} // namespace
} // namespace cutaway::test
