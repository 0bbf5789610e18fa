// The tiles the ray caster's operator shader runs over (render/raycast/raycaster.hpp,
// tilesCovering): every pixel whose ray meets an operator's box must lie in
// them, or the box would vanish from the image there; the fewer others, the
// less the operators' code costs the rays that miss it. (No device needed;
// the function lives beside the ray caster. That the two shaders together
// render what the operators' shader alone renders, to the bit, is
// OperatorRegionsRender.SkippingChangesNoPixel.)
#include "operators/operator_geometry.hpp"
#include "render/camera.hpp"
#include "render/raycast/raycaster.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <random>

namespace cutaway::test {
namespace {

const glm::uvec2 kSize(200, 120);

render::CameraMatrices cameraFor(bool perspective, double azimuth) {
    Camera camera;
    camera.projection = perspective ? Projection::Perspective : Projection::Orthographic;
    camera.azimuthDeg = azimuth;
    camera.elevationDeg = 25.0;
    const render::Box bounds{glm::dvec3(-50.0), glm::dvec3(50.0)};
    return render::computeCamera(camera, bounds, int(kSize.x), int(kSize.y));
}

// The corners of the world box [lo, hi].
std::vector<glm::dvec3> corners(glm::dvec3 lo, glm::dvec3 hi) {
    const auto c = operators::WorldBox{glm::dmat4(1.0), {lo, hi}}.corners();
    return {c.begin(), c.end()};
}

// Whether the ray of pixel (x, y), as ray_march.h casts it from the near
// plane on, meets [lo, hi].
bool rayMeets(const render::CameraMatrices& cam, int x, int y, glm::dvec3 lo, glm::dvec3 hi) {
    const glm::dmat4 clipToWorld = glm::inverse(cam.viewProj);
    const glm::dvec2 ndc = (glm::dvec2(x, y) + 0.5) / glm::dvec2(kSize) * 2.0 - 1.0;
    const glm::dvec4 nearH = clipToWorld * glm::dvec4(ndc, 0.0, 1.0);
    const glm::dvec4 farH = clipToWorld * glm::dvec4(ndc, 1.0, 1.0);
    const glm::dvec3 origin = glm::dvec3(nearH) / nearH.w;
    const glm::dvec3 dir = glm::dvec3(farH) / farH.w - origin;
    double t0 = 0.0, t1 = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(dir[a]) < 1e-300) {
            if (origin[a] < lo[a] || origin[a] > hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - origin[a]) / dir[a], tb = (hi[a] - origin[a]) / dir[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 <= t1;
}

} // namespace

TEST(OperatorTiles, CoverEveryPixelWhoseRayMeetsTheBox) {
    const glm::uvec2 tiles((kSize + 7u) / 8u);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-40.0, 40.0), e(2.0, 20.0);
    int partial = 0, boxes = 0;
    for (const bool perspective : {true, false})
        for (int n = 0; n < 40; ++n, ++boxes) {
            SCOPED_TRACE(std::string(perspective ? "perspective" : "orthographic") + " box " +
                         std::to_string(n));
            const render::CameraMatrices cam = cameraFor(perspective, 17.0 * n);
            const glm::dvec3 centre(u(rng), u(rng), u(rng));
            const glm::dvec3 half(e(rng), e(rng), e(rng));
            const glm::dvec3 lo = centre - half, hi = centre + half;
            const render::TileRect rect =
                render::tilesCovering(cam.viewProj, corners(lo, hi), kSize);
            ASSERT_FALSE(rect.empty());
            EXPECT_TRUE(glm::all(glm::lessThanEqual(rect.hi, tiles)));
            partial += (rect.hi.x - rect.lo.x) * (rect.hi.y - rect.lo.y) < tiles.x * tiles.y / 2;
            int met = 0;
            for (int y = 0; y < int(kSize.y); ++y)
                for (int x = 0; x < int(kSize.x); ++x) {
                    if (!rayMeets(cam, x, y, lo, hi)) continue;
                    ++met;
                    const glm::uvec2 tile(glm::uvec2(x, y) / 8u);
                    ASSERT_TRUE(glm::all(glm::greaterThanEqual(tile, rect.lo)) &&
                                glm::all(glm::lessThan(tile, rect.hi)))
                        << "pixel " << x << "," << y << " outside the operator's tiles";
                }
            EXPECT_GT(met, 0);
        }
    // Boxes a fifth of the view wide or less: most leave over half the image
    // to the volume's shader.
    EXPECT_GT(partial, boxes * 3 / 4);
}

TEST(OperatorTiles, AllWhenABoxReachesBehindTheEyeNoneWhenItIsOffScreen) {
    const render::CameraMatrices cam = cameraFor(true, 30.0);
    // A box around the eye: some of its corners lie behind it.
    const render::TileRect all =
        render::tilesCovering(cam.viewProj, corners(cam.eye - 5.0, cam.eye + 5.0), kSize);
    EXPECT_EQ(all.lo, glm::uvec2(0));
    EXPECT_EQ(all.hi, glm::uvec2(25, 15));
    // A box far to the side of the view, in front of the eye.
    const glm::dvec3 side = glm::normalize(glm::cross(cam.forward, glm::dvec3(0.0, 0.0, 1.0)));
    const glm::dvec3 away = cam.eye + cam.forward * 200.0 + side * 5000.0;
    EXPECT_TRUE(
        render::tilesCovering(cam.viewProj, corners(away - 5.0, away + 5.0), kSize).empty());
    EXPECT_TRUE(render::tilesCovering(cam.viewProj, {}, kSize).empty());
}

} // namespace cutaway::test
