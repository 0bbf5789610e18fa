#include "gpu_fixture.hpp"

#include "bake/feature_bake.hpp"
#include "bake/gradient_bake.hpp"
#include "job/render_job.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"

#include <cmath>
#include <glm/gtc/packing.hpp>

namespace cutaway::test {

nlohmann::json operatorPhantomDocument() {
    return nlohmann::json::parse(R"({"version": 1,
        "volume": {"phantom": "head", "size": [64, 64, 64]},
        "labels": {"phantom": true},
        "transfer": {"points": [{"value": 0, "color": [0, 0, 0], "alpha": 0},
            {"value": 50, "color": [0.9, 0.7, 0.6], "alpha": 0},
            {"value": 80, "color": [0.9, 0.7, 0.6], "alpha": 0.05},
            {"value": 115, "color": [0.9, 0.5, 0.5], "alpha": 0.2},
            {"value": 200, "color": [1, 1, 0.9], "alpha": 0.9}]},
        "camera": {"orbit": {"azimuth": 35, "elevation": 40}},
        "render": {"size": [96, 96], "background": "transparent"}})");
}

std::vector<nlohmann::json> phantomOperatorCases() {
    return {nlohmann::json::array(), nlohmann::json::parse(R"([{ "type": "peeler",
                  "placement": { "translate": [0, 0, 16], "scale": [50, 50, 30] },
                  "params": { "hinge": -10, "thickness": 12, "angle": 130 },
                  "alignment": {"mode": "surface", "threshold": 30, "depth": 3, "band": 2} }])"),
            nlohmann::json::parse(R"([{ "type": "retractor",
                  "placement": { "translate": [0, -10, 14], "scale": [30, 40, 30] },
                  "params": { "opening": 14 },
                  "alignment": {"mode": "segment", "labels": ["brain"], "band": 2} }])")};
}

Scene headScene(int phantomSize, int width, int height) {
    Scene s;
    s.volume.phantom = "head";
    s.volume.phantomSize = glm::ivec3(phantomSize);
    s.transfer.points = {{0.0, {0, 0, 0}, 0.0f},
                         {50.0, {0.9f, 0.7f, 0.6f}, 0.0f},
                         {80.0, {0.9f, 0.7f, 0.6f}, 0.05f},
                         {115.0, {0.9f, 0.5f, 0.5f}, 0.2f},
                         {200.0, {1.0f, 1.0f, 0.9f}, 0.9f},
                         {255.0, {1.0f, 1.0f, 0.9f}, 1.0f}};
    s.camera.azimuthDeg = 0.0;
    s.camera.elevationDeg = 0.0;
    s.render.width = width;
    s.render.height = height;
    s.render.background = glm::vec4(0.0f);
    s.lights.directional.clear();
    return s;
}

std::vector<float> downloadFeatureField(const gpu::Context& ctx, const gpu::Image& image) {
    EXPECT_EQ(image.format, VK_FORMAT_R16_SFLOAT);
    const std::vector<std::byte> bytes = gpu::downloadImage(ctx, image, bake::kFeatureLayout, 2);
    std::vector<float> out(bytes.size() / 2);
    const auto* halves = reinterpret_cast<const uint16_t*>(bytes.data());
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = glm::unpackHalf1x16(halves[i]);
    return out;
}

Image renderVolume(const gpu::Context& ctx, const Scene& scene, const Volume& volume) {
    bake::GradientBaker baker(ctx);
    render::GpuVolume gv = render::prepareVolume(ctx, baker, std::make_shared<Volume>(volume),
                                                 job::sceneWindow(scene, volume));
    render::VolumeRenderer renderer(ctx);
    return renderer.render(scene, gv);
}

Image renderScene(const gpu::Context& ctx, const Scene& scene) {
    return renderVolume(ctx, scene, job::loadSceneVolume(scene));
}

ImageDiff compareImages(const Image& a, const Image& b) {
    ImageDiff d;
    if (a.width != b.width || a.height != b.height) {
        d.maxAbs = INFINITY;
        d.rms = INFINITY;
        d.meanAbs = INFINITY;
        return d;
    }
    double sum2 = 0.0, sum1 = 0.0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) {
        const float e = std::abs(a.rgba[i] - b.rgba[i]);
        d.maxAbs = std::max(d.maxAbs, e);
        sum2 += double(e) * e;
        sum1 += e;
    }
    d.rms = std::sqrt(sum2 / static_cast<double>(a.rgba.size()));
    d.meanAbs = sum1 / static_cast<double>(a.rgba.size());
    return d;
}

bool GpuTest::filtersInFloat() const {
    return ctx().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

void GpuTest::expectAgree(const Image& a, const Image& b, float precise, const std::string& what,
                          double quantizedRms) const {
    const ImageDiff d = compareImages(a, b);
    const bool agree = filtersInFloat() ? d.maxAbs <= precise
                                        : d.maxAbs <= kQuantizedMaxAbs && d.rms <= quantizedRms;
    EXPECT_TRUE(agree) << what << ": max " << d.maxAbs << ", rms " << d.rms << " on "
                       << ctx().deviceName();
}

} // namespace cutaway::test
