// Determinism: the same scene on the same machine
// renders bit-identical pixels, whether the renderer is fresh or has cached
// the volume, the fields and the pipelines of an earlier frame, and for both
// render methods.
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"

#include <cstring>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

using nlohmann::json;

json sceneWith(const json& operators, const char* method) {
    return {
        {"version", 1},
        {"volume", {{"phantom", "head"}, {"size", {48, 48, 48}}}},
        {"labels", {{"phantom", true}}},
        {"transfer", json::parse(R"({"points": [{"value": 0, "color": [0.9, 0.7, 0.6], "alpha": 0},
              {"value": 60, "color": [0.9, 0.7, 0.6], "alpha": 0.05},
              {"value": 200, "color": [1, 1, 0.9], "alpha": 0.8}]})")},
        {"camera", {{"orbit", {{"azimuth", 40}, {"elevation", 35}, {"distance", 170}}}}},
        {"render", {{"size", {64, 56}}, {"method", method}}},
        {"operators", operators},
    };
}

bool identical(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.rgba.size() == b.rgba.size() &&
           std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
}

class Determinism : public GpuTest {};

TEST_F(Determinism, TheSameSceneRendersTheSamePixels) {
    const json peeler = json::array(
        {{{"type", "peeler"},
          {"placement", {{"translate", {0, 0, 12}}, {"scale", {36, 36, 22}}}},
          {"alignment", {{"mode", "surface"}, {"threshold", "otsu"}, {"depth", 3}}},
          {"params", {{"hinge", -8}, {"thickness", 14}, {"radius", 3}, {"angle", 120}}}}});
    for (const json& document :
         {sceneWith(peeler, "slicing"), sceneWith(json::array(), "raycast")}) {
        const Scene scene = parseScene(document, "/nonexistent", "test");
        const Image first = job::renderImage(ctx(), scene);
        job::FrameRenderer renderer(ctx());
        const Image fresh = renderer.render(scene);
        const Image cached = renderer.render(scene); // volume, fields, pipelines kept
        double alpha = 0.0;
        for (std::size_t i = 3; i < first.rgba.size(); i += 4)
            alpha += first.rgba[i];
        ASSERT_GT(alpha, 100.0) << "the head must be visible for the comparison to mean much";
        EXPECT_TRUE(identical(first, fresh)) << document["render"]["method"];
        EXPECT_TRUE(identical(first, cached)) << document["render"]["method"];
    }
}

} // namespace
} // namespace cutaway::test
