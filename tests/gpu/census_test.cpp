// The ray caster's census (VolumeRenderer::setCensus, bench --census): per
// pixel, how many samples its ray took of each kind. The benchmark's figures
// of where a frame's work goes come from it, so its counts must agree with
// the colour the same rays composite and with what the skipping saves.
#include "bake/gradient_bake.hpp"
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"
#include "scene/scene.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

// The head phantom ray cast with a peeler whose flap swings out into the air
// (or without an operator), over a transparent background.
Scene censusScene(bool withOperator) {
    nlohmann::json doc = operatorPhantomDocument();
    doc["operators"] = nlohmann::json::array();
    if (withOperator) {
        doc["operators"].push_back(nlohmann::json::parse(
            R"({ "type": "peeler", "placement": { "translate": [0, 0, 16], "scale": [50, 50, 30] },
                 "params": { "hinge": -10, "thickness": 12, "angle": 130 },
                 "alignment": { "mode": "surface", "threshold": 30, "depth": 3, "band": 2 } })"));
    }
    doc["render"]["method"] = "raycast";
    doc["render"]["background"] = {0, 0, 0, 0};
    return parseScene(doc, "/nonexistent", "test");
}

struct Totals {
    double count[4] = {0.0, 0.0, 0.0, 0.0};
};

} // namespace

class Census : public GpuTest {};

TEST_F(Census, CountsTheSamplesTheColourCameFrom) {
    for (const bool withOperator : {false, true}) {
        SCOPED_TRACE(withOperator ? "peeler" : "no operator");
        const Scene scene = censusScene(withOperator);
        const auto volume = std::make_shared<const Volume>(job::loadSceneVolume(scene));
        bake::GradientBaker baker(ctx());
        const render::GpuVolume gv = render::prepareVolume(
            ctx(), baker, volume, job::sceneWindow(scene, *volume), std::nullopt, nullptr);
        render::VolumeRenderer renderer(ctx());
        const Image colour = renderer.render(scene, gv);
        renderer.setCensus(true);
        const Image census = renderer.render(scene, gv);
        renderer.setOperatorSkipping(false);
        const Image unskipped = renderer.render(scene, gv);
        renderer.setOperatorSkipping(true);
        renderer.setCensus(false);
        // Counting leaves the colour pipeline as it was.
        EXPECT_EQ(compareImages(colour, renderer.render(scene, gv)).maxAbs, 0.0f);

        ASSERT_EQ(census.rgba.size(), colour.rgba.size());
        Totals totals, whole;
        int shown = 0;
        for (std::size_t i = 0; i < census.rgba.size(); i += 4) {
            const float* n = &census.rgba[i];
            for (int c = 0; c < 4; ++c) {
                ASSERT_GE(n[c], 0.0f);
                ASSERT_EQ(n[c], std::floor(n[c])) << "pixel " << i / 4;
                totals.count[c] += n[c];
                whole.count[c] += unskipped.rgba[i + std::size_t(c)];
            }
            // Every slab shaded was fetched (resolved) first.
            EXPECT_LE(n[1], n[0]) << "pixel " << i / 4;
            EXPECT_LE(n[3], n[2]) << "pixel " << i / 4;
            // Colour comes only from shaded slabs.
            if (colour.rgba[i + 3] > 0.0f) {
                ++shown;
                EXPECT_GE(n[1] + n[3], 1.0f) << "pixel " << i / 4;
            }
        }
        EXPECT_GT(shown, 1000);
        EXPECT_GT(totals.count[0], totals.count[1]);
        EXPECT_GT(totals.count[1], 0.0);
        if (!withOperator) {
            EXPECT_EQ(totals.count[2], 0.0);
            EXPECT_EQ(totals.count[3], 0.0);
            continue;
        }
        EXPECT_GT(totals.count[3], 0.0);
        // Stepping over the operator's empty blocks saves resolves and shades
        // the same slabs (the image is the same: operator_regions_test.cpp).
        EXPECT_LT(totals.count[2], 0.9 * whole.count[2]);
        EXPECT_EQ(totals.count[3], whole.count[3]);
    }
}

} // namespace cutaway::test
