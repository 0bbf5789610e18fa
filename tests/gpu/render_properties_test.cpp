// Properties of the slicing renderer that a wrong implementation would break.
// Images are small (tens of pixels) and phantoms coarse so lavapipe is quick.
#include "bake/gradient_bake.hpp"
#include "gpu_fixture.hpp"
#include "io/exr.hpp"
#include "job/render_job.hpp"
#include "render/camera.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

// Andrew's monotone chain: counter-clockwise hull of 2D points.
std::vector<glm::dvec2> convexHull(std::vector<glm::dvec2> pts) {
    std::sort(pts.begin(), pts.end(),
              [](auto a, auto b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    auto cross = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<glm::dvec2> hull(2 * pts.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0)
            --k;
        hull[k++] = pts[i];
    }
    for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0)
            --k;
        hull[k++] = pts[i - 1];
    }
    hull.resize(k - 1);
    return hull;
}

// Largest signed distance outside the hull's edges (negative inside).
double outsideDistance(const std::vector<glm::dvec2>& hull, glm::dvec2 p) {
    double d = -1e30;
    for (std::size_t i = 0; i < hull.size(); ++i) {
        glm::dvec2 a = hull[i], b = hull[(i + 1) % hull.size()];
        glm::dvec2 e = glm::normalize(b - a);
        glm::dvec2 outward(e.y, -e.x); // right of a CCW edge
        d = std::max(d, glm::dot(p - a, outward));
    }
    return d;
}

float alphaAt(const Image& img, int x, int y) {
    return img.pixel(x, y)[3];
}

} // namespace

TEST_F(GpuTest, NothingIsDrawnOutsideTheProjectedBox) {
    Scene scene = headScene(32, 80, 60);
    scene.camera.azimuthDeg = 35.0;
    scene.camera.elevationDeg = 25.0;
    scene.camera.distance = 70.0; // close: the box fills much of the view
    Image img = renderScene(ctx(), scene);

    const glm::dvec3 h(16.0);
    render::CameraMatrices cam =
        render::computeCamera(scene.camera, render::Box{-h, h}, img.width, img.height);
    std::vector<glm::dvec2> corners;
    for (int i = 0; i < 8; ++i) {
        glm::dvec4 c = cam.viewProj * glm::dvec4((i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y,
                                                 (i & 4) ? h.z : -h.z, 1.0);
        corners.emplace_back((c.x / c.w * 0.5 + 0.5) * img.width,
                             (c.y / c.w * 0.5 + 0.5) * img.height);
    }
    const auto hull = convexHull(corners);
    int inside = 0, covered = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const double d = outsideDistance(hull, {x + 0.5, y + 0.5});
            const float* p = img.pixel(x, y);
            if (d > 1.0) {
                ASSERT_EQ(p[0], 0.0f) << "pixel " << x << "," << y << " outside the box";
                ASSERT_EQ(p[3], 0.0f) << "pixel " << x << "," << y << " outside the box";
            } else if (d < -1.0) {
                ++inside;
                covered += p[3] > 0.0f;
            }
        }
    ASSERT_GT(inside, 200);
    EXPECT_GT(covered, inside / 4) << "the volume should cover much of its projected box";
}

TEST_F(GpuTest, SymmetricPhantomUnderSymmetricViewGivesSymmetricImage) {
    const auto mirrored = [](Image img) {
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width / 2; ++x)
                for (int c = 0; c < 4; ++c)
                    std::swap(img.pixel(x, y)[c], img.pixel(img.width - 1 - x, y)[c]);
        return img;
    };
    Scene scene = headScene(48, 64, 48);
    const Image img = renderScene(ctx(), scene);
    float total = 0.0f;
    for (float v : img.rgba)
        total += v;
    EXPECT_GT(total, 10.0f) << "image is empty";
    // Float rasterization and 8-bit gradients: measured ~1e-6 on lavapipe. The
    // mirrored sample points round otherwise (expectAgree), and a GPU's rounding
    // weighs more in this small image: rms 4.8e-3 on an H200.
    const double quantizedRms = 8e-3;
    expectAgree(img, mirrored(img), 2e-3f, "mirrored", quantizedRms);

    // The same check must fail when the view is not symmetric, on any device.
    scene.camera.azimuthDeg = 25.0;
    const Image turned = renderScene(ctx(), scene);
    const ImageDiff asym = compareImages(turned, mirrored(turned));
    EXPECT_GT(asym.maxAbs, 0.05f);
    EXPECT_GT(asym.rms, 2.0 * quantizedRms); // 0.020 on lavapipe
}

TEST_F(GpuTest, HalvingSliceSpacingWithOpacityCorrectionChangesLittle) {
    Scene scene = headScene(48, 64, 64);
    scene.camera.azimuthDeg = 20.0;
    scene.camera.elevationDeg = 10.0;
    scene.render.sliceSpacing = 1.0;
    Image coarse = renderScene(ctx(), scene);
    scene.render.sliceSpacing = 0.5;
    Image fine = renderScene(ctx(), scene);
    ImageDiff d = compareImages(coarse, fine);
    // Tolerance: mean absolute difference 0.004, RMS 0.01 per channel (values in [0, 1]).
    EXPECT_LT(d.meanAbs, 0.004) << "max " << d.maxAbs << " rms " << d.rms;
    EXPECT_LT(d.rms, 0.01) << "max " << d.maxAbs;
}

// /transfer/unit_distance: alphas are opacities per that many mm. A block of
// uniform translucent material on 2 mm voxels, and the same block on 1 mm
// voxels: given as the coarse spacing the unit changes nothing on the coarse
// block, and the fine block looks as the coarse one does, where its default
// unit (its own voxel) makes it denser. Control: the default unit on the fine
// block. Tolerance: mean 0.002 per channel.
TEST_F(GpuTest, UnitDistanceKeepsOpacityPerMm) {
    const auto block = [](int side, double spacing) {
        Volume v = Volume::allocate(glm::ivec3(side), VoxelType::U8, glm::dvec3(spacing));
        std::fill(v.data.begin(), v.data.end(), std::byte{100});
        return v;
    };
    const Volume coarse = block(16, 2.0), fine = block(32, 1.0);
    Scene scene = headScene(8, 48, 48);
    scene.camera.azimuthDeg = 20.0;
    scene.camera.elevationDeg = 30.0;
    scene.volume.window = std::array<double, 2>{0.0, 255.0};
    scene.transfer.points = {{0.0, {1, 1, 1}, 0.0f}, {255.0, {0.9f, 0.6f, 0.5f}, 0.1f}};
    const Image reference = renderVolume(ctx(), scene, coarse);
    Scene given = scene;
    given.unitDistance = 2.0;
    EXPECT_EQ(renderVolume(ctx(), given, coarse).rgba, reference.rgba);
    Scene onFine = scene;
    onFine.render.sliceSpacing = 2.0; // the same slabs in mm
    const double denser = compareImages(renderVolume(ctx(), onFine, fine), reference).meanAbs;
    onFine.unitDistance = 2.0;
    const double same = compareImages(renderVolume(ctx(), onFine, fine), reference).meanAbs;
    EXPECT_LT(same, 0.002) << "default unit: " << denser;
    EXPECT_GT(denser, 10.0 * same) << "control: the fine voxels' own unit";
}

TEST_F(GpuTest, AnisotropicSpacingKeepsASphereRound) {
    // 48 x 48 x 24 voxels of 1 x 1 x 2 mm: a 48 mm cube holding a sphere of radius 18 mm.
    const glm::ivec3 dims(48, 48, 24);
    const glm::dvec3 spacing(1.0, 1.0, 2.0);
    Volume v = Volume::allocate(dims, VoxelType::U8, spacing);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                glm::dvec3 p = (glm::dvec3(x, y, z) + 0.5) * spacing - 24.0;
                double inside = std::clamp(18.0 - glm::length(p) + 0.5, 0.0, 1.0);
                v.data[v.index(x, y, z)] = static_cast<std::byte>(std::lround(200.0 * inside));
            }
    Scene scene = headScene(8, 96, 96);
    scene.camera.projection = Projection::Orthographic;
    scene.camera.orthoHeight = 64.0;
    scene.transfer.points = {
        {0.0, {1, 1, 1}, 0.0f}, {90.0, {1, 1, 1}, 0.0f}, {110.0, {1, 1, 1}, 1.0f}};
    Image img = renderVolume(ctx(), scene, v);

    int minX = img.width, maxX = -1, minY = img.height, maxY = -1;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (alphaAt(img, x, y) > 0.5f) {
                minX = std::min(minX, x), maxX = std::max(maxX, x);
                minY = std::min(minY, y), maxY = std::max(maxY, y);
            }
    ASSERT_GE(maxX, 0) << "sphere not visible";
    const double pxPerMm = 96.0 / 64.0;
    EXPECT_NEAR((maxX - minX + 1) / pxPerMm, 36.0, 2.5);
    EXPECT_NEAR((maxY - minY + 1) / pxPerMm, 36.0, 2.5); // would be 18 mm if spacing were ignored
}

TEST_F(GpuTest, BackgroundIsCompositedBehindTheVolume) {
    Scene scene = headScene(32, 40, 30);
    Image clear = renderScene(ctx(), scene);
    EXPECT_EQ(alphaAt(clear, 0, 0), 0.0f);
    EXPECT_EQ(clear.pixel(0, 0)[0], 0.0f);

    scene.render.background = glm::vec4(0.2f, 0.3f, 0.4f, 1.0f);
    Image grey = renderScene(ctx(), scene);
    const float* corner = grey.pixel(0, 0);
    EXPECT_FLOAT_EQ(corner[0], 0.2f);
    EXPECT_FLOAT_EQ(corner[1], 0.3f);
    EXPECT_FLOAT_EQ(corner[2], 0.4f);
    EXPECT_FLOAT_EQ(corner[3], 1.0f);
    // In the middle the volume covers part of the background: colour = vol + (1 - a) * bg.
    const float* mid = grey.pixel(20, 15);
    const float* midClear = clear.pixel(20, 15);
    EXPECT_NEAR(mid[2], midClear[2] + (1.0f - midClear[3]) * 0.4f, 1e-5f);
    EXPECT_FLOAT_EQ(mid[3], 1.0f);
}

TEST_F(GpuTest, OrthographicAndPerspectiveBothFrameTheVolume) {
    Scene scene = headScene(32, 48, 48);
    for (Projection p : {Projection::Perspective, Projection::Orthographic}) {
        scene.camera.projection = p;
        Image img = renderScene(ctx(), scene);
        EXPECT_EQ(alphaAt(img, 0, 0), 0.0f);
        EXPECT_GT(alphaAt(img, 24, 24), 0.5f);
    }
}

// The default camera (distance 0) fits the volume, not the operators: an
// operator that moves through a sequence must not zoom the view. A pliers
// without displacement changes nothing, wherever it is, inside the volume or
// far outside it; each frame equals the render without it.
TEST_F(GpuTest, TheDefaultFramingDoesNotFollowTheOperators) {
    const auto scene = [](const std::string& operators) {
        return parseScene(nlohmann::json::parse(R"({ "version": 1,
            "volume": { "phantom": "head", "size": [32, 32, 32] },
            "render": { "size": [40, 40], "background": "transparent" },
            "operators": )" + operators + "}"),
                          "/nonexistent", "test");
    };
    const Image plain = renderScene(ctx(), scene("[]"));
    double coverage = 0.0;
    for (std::size_t i = 3; i < plain.rgba.size(); i += 4)
        coverage += plain.rgba[i];
    ASSERT_GT(coverage, 100.0);
    for (const char* at : {"[0, 0, 0]", "[30, 0, 20]", "[0, 0, 90]", "[4000, 0, 0]"}) {
        SCOPED_TRACE(at);
        const Image still = renderScene(
            ctx(),
            scene(std::string(R"([{ "type": "pliers", "placement": { "translate": )") + at +
                  R"(, "scale": [20, 20, 20] }, "params": { "displacement": [0, 0, 0] } }])"));
        expectAgree(plain, still, 2e-3f, "pliers that move nothing");
    }
}

TEST_F(GpuTest, ExrReadBackEqualsRenderedPixels) {
    Scene scene = headScene(32, 37, 23); // odd sizes catch stride mistakes
    scene.camera.azimuthDeg = 40.0;
    Image img = renderScene(ctx(), scene);
    const auto dir = std::filesystem::temp_directory_path() / "cutaway_exr_roundtrip";
    std::filesystem::create_directories(dir);

    ExrOptions full;
    full.halfFloat = false;
    writeExr(dir / "float.exr", img, full);
    Image back = readExr(dir / "float.exr");
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    EXPECT_EQ(back.rgba, img.rgba); // bit-exact

    writeExr(dir / "half.exr", img, {});
    Image halfBack = readExr(dir / "half.exr");
    for (std::size_t i = 0; i < img.rgba.size(); ++i)
        ASSERT_NEAR(halfBack.rgba[i], img.rgba[i], std::abs(img.rgba[i]) * 0x1p-11f + 6e-8f) << i;
    std::filesystem::remove_all(dir);
}

} // namespace cutaway::test

namespace cutaway::test {

// The renderer keeps its classification table between frames: changing what
// the table depends on must remake it.
TEST_F(GpuTest, AReusedRendererFollowsTransferAndSpacingChanges) {
    Scene a = headScene(32, 40, 40);
    Scene b = a;
    b.transfer.points[4].color = {0.2f, 0.9f, 0.3f}; // a green skull
    Scene c = b;
    c.render.sliceSpacing = 0.5;
    const Volume volume = job::loadSceneVolume(a);
    bake::GradientBaker baker(ctx());
    const render::GpuVolume gv = render::prepareVolume(
        ctx(), baker, std::make_shared<Volume>(volume), job::sceneWindow(a, volume));
    render::VolumeRenderer reused(ctx());
    reused.render(a, gv);
    const Image b1 = reused.render(b, gv);
    const Image c1 = reused.render(c, gv);
    EXPECT_EQ(b1.rgba, renderVolume(ctx(), b, volume).rgba);
    EXPECT_EQ(c1.rgba, renderVolume(ctx(), c, volume).rgba);
    EXPECT_GT(compareImages(b1, renderVolume(ctx(), a, volume)).maxAbs, 0.1f);
}

// A whole-number shininess takes its highlight by repeated squaring (the
// specialization constant cwWholeShininess), any other by pow: the two agree.
// Shininess n + 0.0005 takes pow and differs from x^n by at most
// 0.0005 / (e n) (about 1e-5); a power one off (x^(n + 1) for x^n) moved
// the images by 0.006-0.029. Both methods; the highlight itself must show
// (the control: no specular at all).
TEST_F(GpuTest, WholeNumberShininessLightsAsPowDoes) {
    for (RenderMethod method : {RenderMethod::Slicing, RenderMethod::Raycast})
        for (float n : {32.0f, 20.0f, 7.0f}) {
            SCOPED_TRACE(std::to_string(int(n)) +
                         (method == RenderMethod::Raycast ? " raycast" : " slicing"));
            Scene scene = headScene(48, 64, 64);
            scene.camera.azimuthDeg = 30.0;
            scene.camera.elevationDeg = 20.0;
            scene.render.method = method;
            scene.render.shading.specular = 0.8f;
            scene.render.shading.shininess = n;
            const Image whole = renderScene(ctx(), scene);
            scene.render.shading.shininess = n + 0.0005f;
            const Image power = renderScene(ctx(), scene);
            scene.render.shading.specular = 0.0f;
            const Image none = renderScene(ctx(), scene);
            EXPECT_GT(compareImages(whole, none).maxAbs, 0.05f) << "control: a highlight";
            const ImageDiff d = compareImages(whole, power);
            EXPECT_LT(d.maxAbs, 1e-3f) << "rms " << d.rms;
        }
}

} // namespace cutaway::test
