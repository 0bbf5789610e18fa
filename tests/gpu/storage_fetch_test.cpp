// The volume's values (and below, the gradients) read as a storage image and
// filtered in the shader (sample_common.h's volumeAt, on by default on CPU
// devices) against the value texture sampled by the device: the same
// trilinear, clamped-to-edge filter, so the images agree but for the
// filter's arithmetic. lavapipe weights 8-bit textures with 8-bit fractions
// where the shader weighs in float, so an R8 volume's images differ a little
// (and must: the same image to the bit would mean the storage path never
// ran); an R16 volume's agree closely. Both methods, with and without an
// operator, both formats. The surface-aligned operator's distance field is
// loaded and filtered too (operator_sample.h's featureFiltered, and its six
// texels for the feature's direction): a filter with two axes swapped, or
// the direction's neighbours taken along the wrong axes, fails the R16 case
// (checked by breaking each once).
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

class StorageFetch : public GpuTest {};

// The CPU devices' profile, with the values loaded or sampled.
gpu::DeviceTuning cpuTuning(bool storageValues) {
    gpu::DeviceTuning tuning = gpu::kCpuTuning;
    tuning.storageValues = storageValues;
    return tuning;
}

// Renders `scene` of `gv` with the values sampled and with them loaded.
std::pair<Image, Image> bothWays(const gpu::Context& ctx, const Scene& scene,
                                 const render::GpuVolume& gv) {
    render::VolumeRenderer sampling(ctx, cpuTuning(false));
    Image sampled = sampling.render(scene, gv);
    render::VolumeRenderer loading(ctx, cpuTuning(true));
    Image loaded = loading.render(scene, gv);
    return {std::move(sampled), std::move(loaded)};
}

TEST_F(StorageFetch, RendersAsTheSampledTextureDoes) {
    if (!ctx().formats().storageValues)
        GTEST_SKIP() << ctx().deviceName() << " cannot store R8 and R16 images (lavapipe can)";
    // The head phantom's 8-bit values over [0, 255] upload as R8; over a
    // narrower window, as R16.
    const std::pair<const char*, VkFormat> windows[] = {{"[0, 255]", VK_FORMAT_R8_UNORM},
                                                        {"[20, 235]", VK_FORMAT_R16_UNORM}};
    for (const auto& [window, format] : windows)
        for (const nlohmann::json& ops : phantomOperatorCases())
            for (const char* method : {"slicing", "raycast"}) {
                nlohmann::json doc = operatorPhantomDocument();
                doc["volume"]["window"] = nlohmann::json::parse(window);
                doc["operators"] = ops;
                doc["render"]["method"] = method;
                const Scene scene = parseScene(doc, "/nonexistent", "test");
                SCOPED_TRACE(std::string(window) + " " + method + " " +
                             (scene.operators.empty() ? "no operator" : scene.operators[0].name));
                const auto volume = std::make_shared<const Volume>(job::loadSceneVolume(scene));
                const bake::GradientBaker baker(ctx(), cpuTuning(true));
                const render::GpuVolume gv =
                    render::prepareVolume(ctx(), baker, volume, job::sceneWindow(scene, *volume),
                                          std::nullopt, job::loadSceneLabels(scene, volume));
                ASSERT_EQ(gv.values.format, format);
                const auto [sampled, loaded] = bothWays(ctx(), scene, gv);
                double coverage = 0.0;
                for (std::size_t i = 3; i < loaded.rgba.size(); i += 4)
                    coverage += loaded.rgba[i];
                EXPECT_GT(coverage, 1000.0) << "the head must show";
                const ImageDiff d = compareImages(sampled, loaded);
                // Measured on lavapipe: R8 up to 0.0083, rms 4.2e-4; R16 up to
                // 2.6e-5 (float rounding: lavapipe weighs 16-bit texels in
                // float too). A filter that mixed up two axes or missed the
                // clamp moves whole edges by more than 0.1.
                // A GPU weighs 16-bit texels in 8 bits too (expectAgree): up to
                // 0.0033 on an H200 for the values, and 0.14 in single pixels
                // with the peeler, whose distance field it filters
                // so too: the mask's edge moves by a fraction of a voxel. There
                // the rms below is what sees a filter gone wrong.
                const float most = !filtersInFloat()              ? kQuantizedMaxAbs
                                   : format == VK_FORMAT_R8_UNORM ? 0.03f
                                                                  : 1e-4f;
                EXPECT_LT(d.maxAbs, most) << "rms " << d.rms;
                EXPECT_LT(d.rms, 2e-3);
                if (format == VK_FORMAT_R8_UNORM) {
                    EXPECT_GT(d.maxAbs, 0.0f) << "the same to the bit: not loaded and filtered";
                }
            }
}

// The gradients in bricks, loaded and filtered by the shaders (the default on
// CPU devices), against the same gradients on the grid, sampled: the same
// filter, so the images agree but for its arithmetic. Both methods, with and
// without an operator. The bricked image sampled as if it lay on the grid (a
// mix-up of the layouts, or the shaders' bricked path never running) changes
// the image by far more.
TEST_F(StorageFetch, BrickedGradientsRenderAsTheSampledOnesDo) {
    const char* const operators[] = {
        "[]",
        R"([{ "type": "peeler", "placement": { "translate": [0, 0, 16], "scale": [50, 50, 30] },
                   "params": { "hinge": -10, "thickness": 12, "angle": 130 },
                   "alignment": {"mode": "surface", "threshold": 30, "depth": 3, "band": 2} }])"};
    const bake::GradientBaker baker(ctx(), gpu::kCpuTuning);
    render::VolumeRenderer renderer(ctx(), gpu::kCpuTuning);
    for (const char* ops : operators)
        for (const char* method : {"slicing", "raycast"}) {
            nlohmann::json doc = operatorPhantomDocument();
            doc["operators"] = nlohmann::json::parse(ops);
            doc["render"]["method"] = method;
            const Scene scene = parseScene(doc, "/nonexistent", "test");
            SCOPED_TRACE(std::string(method) + (scene.operators.empty() ? "" : " with a peeler"));
            const auto volume = std::make_shared<const Volume>(job::loadSceneVolume(scene));
            render::GpuVolume gv =
                render::prepareVolume(ctx(), baker, volume, job::sceneWindow(scene, *volume));
            const auto renderWith = [&](bake::GradientLayout baked, bake::GradientLayout read) {
                gv.gradients = baker.bake(gv.values, gv.spacing, baked);
                gv.gradientLayout = read;
                return renderer.render(scene, gv);
            };
            const Image sampled =
                renderWith(bake::GradientLayout::Linear, bake::GradientLayout::Linear);
            const Image loaded =
                renderWith(bake::GradientLayout::Bricked, bake::GradientLayout::Bricked);
            const Image mixedUp =
                renderWith(bake::GradientLayout::Bricked, bake::GradientLayout::Linear);
            // Measured on lavapipe, which filters RGBA8 in float too: up
            // to 1.1e-6 apart; a mix-up, rms 0.021.
            expectAgree(sampled, loaded, 1e-5f, "bricked against sampled gradients");
            const ImageDiff wrong = compareImages(sampled, mixedUp);
            EXPECT_GT(wrong.rms, 2.0 * kQuantizedRms) << "max " << wrong.maxAbs;
        }
}

} // namespace
} // namespace cutaway::test
