// The device's tuning (gpu/device_tuning.hpp): the paths that pay only on a
// CPU implementation are decided once, and a device whose profile leaves
// them off pays nothing for them. Forcing the GPU profile on lavapipe, no
// image has storage usage for them, none rests in GENERAL for them, no
// stand-in storage image is made, and no descriptor set layout declares
// their bindings, whatever the frame (both methods, every alignment); and
// the frames still render as the CPU profile's do. The CPU profile, where
// the device can take it, shows each of those checks failing.
#include "bake/gradient_bake.hpp"
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"
#include "scene/scene.hpp"
#include "shared/bindings.h"
#include "shared/gradient.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

namespace cutaway::test {
namespace {

// The CPU paths' bindings, by the name of the set layout that would hold them.
bool declaresStoragePaths(const gpu::SetLayoutRecord& layout) {
    std::set<uint32_t> paths;
    if (layout.name == "slicing frame" || layout.name == "ray caster frame")
        paths = {CW_BIND_VALUES_R8, CW_BIND_VALUES_R16, CW_BIND_GRADIENT_IMAGE};
    else if (layout.name == "operator")
        paths = {CW_BIND_OP_FEATURE_IMAGE};
    else if (layout.name == "gradient bake")
        paths = {CW_GRADIENT_BIND_VALUES_R8, CW_GRADIENT_BIND_VALUES_R16};
    return std::any_of(layout.bindings.begin(), layout.bindings.end(), [&](const auto& b) {
        return paths.count(b.binding) && b.descriptorType == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    });
}

// What a tuning's renders leave behind: whether any of the CPU paths' traces
// is there.
struct Traces {
    bool valuesStorage = false;    ///< the value texture has storage usage
    bool valuesGeneral = false;    ///< and rests in GENERAL
    bool bricked = false;          ///< the gradients are bricked
    bool gradientsGeneral = false; ///< and rest in GENERAL
    int standIns = 0;              ///< stand-in storage images made
    int layouts = 0;               ///< set layouts made, of the four above
    int layoutsWithPaths = 0;      ///< of them, those declaring a CPU path's binding
};

std::vector<nlohmann::json> operatorCases() {
    std::vector<nlohmann::json> cases = phantomOperatorCases();
    cases.push_back(nlohmann::json::parse(R"([{ "type": "retractor",
        "placement": { "translate": [0, -10, 14], "scale": [30, 40, 30] },
        "params": { "opening": 14 } }])")); // axis alignment
    return cases;
}

// Renders every case with both methods under `tuning`, into `images`.
Traces renderAll(const gpu::Context& ctx, const gpu::DeviceTuning& tuning,
                 std::vector<Image>& images) {
    Traces t;
    const std::size_t before = ctx.setLayouts().size();
    const bake::GradientBaker baker(ctx, tuning);
    render::VolumeRenderer renderer(ctx, tuning);
    for (const nlohmann::json& ops : operatorCases())
        for (const char* method : {"slicing", "raycast"}) {
            nlohmann::json doc = operatorPhantomDocument();
            doc["operators"] = ops;
            doc["render"]["method"] = method;
            const Scene scene = parseScene(doc, "/nonexistent", "test");
            const auto volume = std::make_shared<const Volume>(job::loadSceneVolume(scene));
            const render::GpuVolume gv =
                render::prepareVolume(ctx, baker, volume, job::sceneWindow(scene, *volume),
                                      std::nullopt, job::loadSceneLabels(scene, volume));
            images.push_back(renderer.render(scene, gv));
            t.valuesStorage |= (gv.values.usage & VK_IMAGE_USAGE_STORAGE_BIT) != 0;
            t.valuesGeneral |= gv.values.layout == VK_IMAGE_LAYOUT_GENERAL;
            t.bricked |= gv.gradientLayout == bake::GradientLayout::Bricked;
            t.gradientsGeneral |= gv.gradients.layout == VK_IMAGE_LAYOUT_GENERAL;
        }
    t.standIns = renderer.storageStandIns();
    const std::vector<gpu::SetLayoutRecord> layouts = ctx.setLayouts();
    for (std::size_t i = before; i < layouts.size(); ++i) {
        const std::string& name = layouts[i].name;
        if (name == "slicing frame" || name == "ray caster frame" || name == "operator" ||
            name == "gradient bake") {
            ++t.layouts;
            t.layoutsWithPaths += declaresStoragePaths(layouts[i]);
        }
    }
    return t;
}

TEST_F(GpuTest, TheGpuProfileTakesNoCpuPath) {
    std::vector<Image> gpuImages, cpuImages;
    const Traces gpu = renderAll(ctx(), gpu::kGpuTuning, gpuImages);
    EXPECT_FALSE(gpu.valuesStorage);
    EXPECT_FALSE(gpu.valuesGeneral);
    EXPECT_FALSE(gpu.bricked);
    EXPECT_FALSE(gpu.gradientsGeneral);
    EXPECT_EQ(gpu.standIns, 0);
    EXPECT_EQ(gpu.layouts, 4) << "the slicing and ray caster frames, operator, gradient bake";
    EXPECT_EQ(gpu.layoutsWithPaths, 0);

    // The control: the CPU profile leaves each trace (where the device can
    // take the storage values; bricked gradients any device can).
    const Traces cpu = renderAll(ctx(), gpu::kCpuTuning, cpuImages);
    const bool values = ctx().formats().storageValues;
    EXPECT_EQ(cpu.valuesStorage, values);
    EXPECT_EQ(cpu.valuesGeneral, true);
    EXPECT_TRUE(cpu.bricked);
    EXPECT_TRUE(cpu.gradientsGeneral);
    EXPECT_GT(cpu.standIns, 0) << "an R8 volume's R16 binding takes a stand-in";
    EXPECT_GT(cpu.layoutsWithPaths, 0);

    // Both profiles render the same frames, but for the filter's arithmetic
    // (the values loaded and weighed in float against sampled ones: up to
    // 0.03 on lavapipe, storage_fetch_test.cpp).
    ASSERT_EQ(gpuImages.size(), cpuImages.size());
    for (std::size_t i = 0; i < gpuImages.size(); ++i) {
        SCOPED_TRACE("case " + std::to_string(i));
        double coverage = 0.0;
        for (std::size_t p = 3; p < gpuImages[i].rgba.size(); p += 4)
            coverage += gpuImages[i].rgba[p];
        EXPECT_GT(coverage, 1000.0) << "the head must show";
        const ImageDiff d = compareImages(gpuImages[i], cpuImages[i]);
        EXPECT_LT(d.maxAbs, filtersInFloat() ? 0.05f : kQuantizedMaxAbs) << "rms " << d.rms;
        EXPECT_LT(d.rms, 2e-3);
    }
}

// Each device takes its own profile: every path on a CPU implementation
// where it can, none on a GPU.
TEST_F(GpuTest, TheDeviceTakesItsTypesProfile) {
    const bool cpu = ctx().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    const gpu::DeviceTuning expected = cpu ? ctx().supported(gpu::kCpuTuning) : gpu::kGpuTuning;
    EXPECT_EQ(ctx().tuning(), expected)
        << ctx().deviceName() << ": " << gpu::tuningName(ctx().tuning());
    EXPECT_EQ(render::VolumeRenderer(ctx()).tuning(), expected);
}

} // namespace
} // namespace cutaway::test
