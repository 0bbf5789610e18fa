// The ray caster's lanes yielding to shading (shaders/glsl/ray_march.h,
// CW_YIELD_LANES; on by default on CPU devices): lanes still stepping over
// transparent samples stop for a pass of shading as soon as one lane of
// their subgroup waits at a visible slab, and go on after it. That changes the
// order of a subgroup's passes, not any ray's samples, so the image is the
// same to the bit as without it: with and without operators, whose runs
// yield too. A lane that shaded a slab it had not found visible, that lost
// the slab it waited at, or that skipped a sample on resuming, changes it.
#include "bake/gradient_bake.hpp"
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"
#include "scene/scene.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

class YieldLanes : public GpuTest {};

TEST_F(YieldLanes, RendersTheSameImageAsLanesThatWait) {
    if (!ctx().computeBallots())
        GTEST_SKIP() << ctx().deviceName() << " has no subgroup ballots in compute shaders";
    for (const nlohmann::json& ops : phantomOperatorCases()) {
        nlohmann::json doc = operatorPhantomDocument();
        doc["operators"] = ops;
        doc["render"]["method"] = "raycast";
        const Scene scene = parseScene(doc, "/nonexistent", "test");
        SCOPED_TRACE(scene.operators.empty() ? "no operator" : scene.operators[0].name);
        const auto volume = std::make_shared<const Volume>(job::loadSceneVolume(scene));
        const bake::GradientBaker baker(ctx());
        const render::GpuVolume gv =
            render::prepareVolume(ctx(), baker, volume, job::sceneWindow(scene, *volume),
                                  std::nullopt, job::loadSceneLabels(scene, volume));
        const render::VolumeRenderer defaults(ctx());
        EXPECT_EQ(defaults.tuning().yieldLanes,
                  ctx().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU);
        gpu::DeviceTuning tuning = ctx().tuning();
        tuning.yieldLanes = false;
        render::VolumeRenderer waitingLanes(ctx(), tuning);
        const Image waiting = waitingLanes.render(scene, gv);
        tuning.yieldLanes = true;
        render::VolumeRenderer yieldingLanes(ctx(), tuning);
        ASSERT_TRUE(yieldingLanes.tuning().yieldLanes);
        const Image yielding = yieldingLanes.render(scene, gv);
        double coverage = 0.0;
        for (std::size_t i = 3; i < yielding.rgba.size(); i += 4)
            coverage += yielding.rgba[i];
        EXPECT_GT(coverage, 1000.0) << "the head must show";
        const ImageDiff d = compareImages(waiting, yielding);
        // lavapipe: the same to the bit (measured). A GPU's compiler may
        // contract the two shaders' arithmetic differently. Lanes that shade
        // a slab they did not find visible moved the image by 0.03-0.08 (the
        // untouched volume's runs) and 0.28-0.85 (an operator's) on lavapipe.
        const bool cpu = ctx().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
        EXPECT_LE(d.maxAbs, cpu ? 0.0f : 1e-5f) << "rms " << d.rms;
        EXPECT_EQ(waiting.operatorIds, yielding.operatorIds);
    }
}

} // namespace
} // namespace cutaway::test
