// /render/filter "cubic" on the device (sample_common.h's volumeAt and
// gradientAt, shared/cubic_filter.h):
//  - as a probe of the values: an opaque, unlit transfer function that maps
//    value to grey shows each pixel's first sample, so a ramp must render
//    as trilinear renders it, and a quadratic a x^2 (x in voxels) darker by
//    a t (1 - t), up to a / 4: cubic is exact where trilinear overestimates.
//    Control: trilinear against itself, which never differs;
//  - on thick slices: the head phantom at 1 x 1 x 3 mm against the same
//    phantom with 0.5 mm slices, and ct_head kept every third slice against
//    the full scan (skipped without ../shared/data), against trilinear
//    filtering of the same thick slices as the control.
#include "gpu_fixture.hpp"
#include "io/picture_difference.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"
#include "volume/phantom.hpp"

#include <cstring>
#include <filesystem>
#include <functional>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

class CubicFilterRender : public GpuTest {};

Scene withFilter(Scene scene, Filter filter) {
    scene.render.filter = filter;
    return scene;
}

// A 16 x 8 x 8 uint16 volume whose value depends on x alone.
Volume alongX(const std::function<double(int)>& f) {
    Volume v = Volume::allocate({16, 8, 8}, VoxelType::U16);
    auto* out = reinterpret_cast<uint16_t*>(v.data.data());
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 16; ++x)
                out[v.index(x, y, z)] = static_cast<uint16_t>(std::lround(f(x)));
    return v;
}

// Grey = value / 10000, opaque, unlit, seen from the front (across x).
Scene probeScene() {
    Scene s = headScene(16, 128, 64);
    s.volume.window = {0.0, 10000.0};
    s.transfer.points = {{0.0, {0, 0, 0}, 1.0f}, {10000.0, {1, 1, 1}, 1.0f}};
    s.render.classification = Classification::Post;
    s.render.shading.enabled = false;
    s.camera.projection = Projection::Orthographic;
    return s;
}

// The red channel of the opaque pixels whose first samples lie 3 voxels or
// more inside the volume along x: the middle 5/8 of the columns it covers.
std::vector<float> interior(const Image& image) {
    int first = image.width, last = -1;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (image.rgba[4 * (std::size_t(y) * image.width + x) + 3] == 1.0f) {
                first = std::min(first, x);
                last = std::max(last, x);
            }
    const int margin = (last - first + 1) * 3 / 16;
    std::vector<float> out;
    for (int y = 0; y < image.height; ++y)
        for (int x = first + margin; x <= last - margin; ++x) {
            const std::size_t i = 4 * (std::size_t(y) * image.width + x);
            if (image.rgba[i + 3] == 1.0f) out.push_back(image.rgba[i]);
        }
    EXPECT_GT(out.size(), 400u) << "the probe must show the volume";
    return out;
}

TEST_F(CubicFilterRender, ReproducesARampAndAQuadratic) {
    const Scene scene = probeScene();
    // Ramp: 600 per voxel, 0.06 of the grey scale.
    const Volume ramp = alongX([](int x) { return 600.0 * x + 500.0; });
    const std::vector<float> rampLinear =
        interior(renderVolume(ctx(), withFilter(scene, Filter::Linear), ramp));
    const std::vector<float> rampCubic =
        interior(renderVolume(ctx(), withFilter(scene, Filter::Cubic), ramp));
    float spread = 0.0f, worst = 0.0f;
    for (std::size_t i = 0; i < rampLinear.size(); ++i) {
        worst = std::max(worst, std::abs(rampCubic[i] - rampLinear[i]));
        spread = std::max(spread, std::abs(rampLinear[i] - rampLinear.front()));
    }
    EXPECT_GT(spread, 0.2f) << "the probe must see the ramp";
    // lavapipe weighs in float: only rounding. A GPU's 8-bit weights err by
    // up to a 256th of a voxel's step (0.06) in each of the eight fetches.
    EXPECT_LT(worst, filtersInFloat() ? 2e-4f : 1e-3f);

    // Quadratic: a = 0.003 of the grey scale per voxel^2, its vertex off
    // the volume (within a cell holding a minimum the cell's range holds it).
    const double a = 0.003;
    const Volume quadratic = alongX([&](int x) { return 1e4 * a * (x + 3.0) * (x + 3.0) + 100.0; });
    const std::vector<float> quadLinear =
        interior(renderVolume(ctx(), withFilter(scene, Filter::Linear), quadratic));
    const std::vector<float> quadCubic =
        interior(renderVolume(ctx(), withFilter(scene, Filter::Cubic), quadratic));
    // Trilinear is a t (1 - t) above the curve, cubic on it: the difference
    // lies in [-a / 4, 0] and reaches below -a / 8 where samples fall near
    // the middle of a cell. The control, trilinear against itself, is 0.
    const float slack = filtersInFloat() ? 2e-5f : 1e-3f;
    float lo = 1.0f, hi = -1.0f;
    for (std::size_t i = 0; i < quadLinear.size(); ++i) {
        lo = std::min(lo, quadCubic[i] - quadLinear[i]);
        hi = std::max(hi, quadCubic[i] - quadLinear[i]);
    }
    EXPECT_GE(lo, float(-a / 4.0) - slack);
    EXPECT_LE(hi, slack);
    EXPECT_LT(lo, float(-a / 8.0));
}

// `fineScene` renders `fine` (linear), `scene` renders `coarse`.
PictureDifference thickAgainstThin(const gpu::Context& ctx, Scene scene, Scene fineScene,
                                   const Volume& fine, const Volume& coarse, Filter filter) {
    // One window for both: each scan's own range would classify them apart.
    const ValueRange range = valueRange(fine);
    scene.volume.window = fineScene.volume.window = std::array<double, 2>{range.min, range.max};
    fineScene.render.filter = Filter::Linear;
    fineScene.render.sliceSpacing =
        0.5 / std::min({fine.spacing.x, fine.spacing.y, fine.spacing.z});
    const Image reference = renderVolume(ctx, fineScene, fine);
    scene.render.filter = filter;
    scene.render.sliceSpacing =
        0.5 / std::min({coarse.spacing.x, coarse.spacing.y, coarse.spacing.z});
    return comparePictures(renderVolume(ctx, scene, coarse), reference);
}

TEST_F(CubicFilterRender, SmoothsTheTerracesOfAThickSlicePhantom) {
    // The same 96 mm head with slices 0.5 mm and 3 mm apart.
    const Volume fine = makePhantom("head", {96, 96, 192}, {1.0, 1.0, 0.5}).values;
    const Volume coarse = makePhantom("head", {96, 96, 32}, {1.0, 1.0, 3.0}).values;
    Scene scene = headScene(96, 96, 96);
    scene.camera.elevationDeg = 20.0; // the steps run across the view
    // A transfer function's opacity is per voxel of the smallest spacing:
    // the 0.5 mm phantom's points take the opacity of half a millimetre.
    Scene fineScene = scene;
    for (auto& point : fineScene.transfer.points)
        point.alpha = 1.0f - std::pow(1.0f - point.alpha, 0.5f);
    const PictureDifference linear =
        thickAgainstThin(ctx(), scene, fineScene, fine, coarse, Filter::Linear);
    const PictureDifference cubic =
        thickAgainstThin(ctx(), scene, fineScene, fine, coarse, Filter::Cubic);
    std::printf("1 x 1 x 3 mm phantom against 0.5 mm: linear %.2f dB, cubic %.2f dB\n", linear.psnr,
                cubic.psnr);
    // Measured on lavapipe: linear 33.0 dB, cubic 34.4 (the phantom's
    // surfaces are sharp steps, which no filter of 3 mm slices recovers).
    EXPECT_GT(cubic.psnr, linear.psnr + 0.8);
}

TEST_F(CubicFilterRender, BringsADecimatedScanCloseToTheFullOne) {
    const std::filesystem::path data(CUTAWAY_SHARED_DATA);
    const std::filesystem::path sceneFile =
        std::filesystem::path(CUTAWAY_SOURCE_DIR) / "scenes" / "ct_head.json";
    if (!std::filesystem::exists(data / "ct_head.nii.gz"))
        GTEST_SKIP() << "ct_head.nii.gz not found in " << data << ": decimated-scan test skipped";
    Scene scene = loadScene(sceneFile);
    scene.render.width = scene.render.height = 256;
    const Volume full = readVolume(data / "ct_head.nii.gz");
    // Every third slice, 3j + 1, so the kept slices keep their places
    // (the volume is centred on its box).
    Volume decimated = Volume::allocate({full.dims.x, full.dims.y, full.dims.z / 3}, full.type,
                                        {full.spacing.x, full.spacing.y, 3.0 * full.spacing.z});
    decimated.direction = full.direction;
    decimated.space = full.space;
    decimated.slope = full.slope;
    decimated.inter = full.inter;
    const std::size_t sliceBytes = std::size_t(full.dims.x) * full.dims.y * voxelSize(full.type);
    for (int z = 0; z < decimated.dims.z; ++z)
        std::memcpy(decimated.data.data() + sliceBytes * z,
                    full.data.data() + sliceBytes * (3 * z + 1), sliceBytes);
    const PictureDifference linear =
        thickAgainstThin(ctx(), scene, scene, full, decimated, Filter::Linear);
    const PictureDifference cubic =
        thickAgainstThin(ctx(), scene, scene, full, decimated, Filter::Cubic);
    std::printf("ct_head every third slice against the full scan: linear %.2f dB, cubic %.2f dB\n",
                linear.psnr, cubic.psnr);
    // Measured on lavapipe at 256 x 256: linear 40.3 dB, cubic 40.9 (the
    // cubic B-spline: 38.8). What 3 mm slices lose of thin structures, no
    // filter brings back; docs/quality.md.
    EXPECT_GT(cubic.psnr, linear.psnr + 0.4);
}

TEST_F(CubicFilterRender, BothMethodsTakeTheSameSamples) {
    for (const nlohmann::json& operators : phantomOperatorCases()) {
        nlohmann::json doc = operatorPhantomDocument();
        doc["operators"] = operators;
        doc["render"]["filter"] = "cubic";
        doc["render"]["termination_opacity"] = 1.0;
        doc["render"]["method"] = "slicing";
        const Image sliced = job::renderImage(ctx(), parseScene(doc, "/nonexistent", "test"));
        doc["render"]["method"] = "raycast";
        const Image cast = job::renderImage(ctx(), parseScene(doc, "/nonexistent", "test"));
        doc["render"]["filter"] = "linear";
        const Image linear = job::renderImage(ctx(), parseScene(doc, "/nonexistent", "test"));
        // Measured on lavapipe: a mean of 4e-7 to 1.1e-6 apart, bound 1e-4;
        // the control, the linear filter's picture, 1.3e-3 to 3.5e-3 away.
        if (!filtersInFloat()) {
            expectAgree(sliced, cast, 0.0f, operators.dump());
            continue;
        }
        const double apart = compareImages(sliced, cast).meanAbs;
        const double control = compareImages(linear, cast).meanAbs;
        EXPECT_LT(apart, 1e-4) << operators.dump();
        EXPECT_GT(control, 1e-3) << operators.dump();
    }
}

} // namespace
} // namespace cutaway::test
