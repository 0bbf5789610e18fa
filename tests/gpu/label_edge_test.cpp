// How smooth a labelled structure's edge is drawn: a sphere known only by
// its labels (its values are those of the tissue around it), shown alone by
// a transfer function of its label, seen from above orthographically. The
// silhouette, its alpha = 0.5 contour, is fitted with a circle; the RMS
// distance of the contour from that circle measures the staircase of the
// label voxels, in pixels, and the fitted radius must be the sphere's.
// Control: the same sphere known by its values (a 1.5 mm smoothstep edge,
// one transfer function), whose silhouette the value reconstruction draws.
#include "bake/gradient_bake.hpp"
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <numbers>

namespace cutaway::test {
namespace {

using nlohmann::json;

constexpr int kGrid = 32;        // voxels of 1 mm along each axis
constexpr int kPixels = 128;     // over kViewMm
constexpr double kViewMm = 32.0; // the orthographic height
constexpr double kRadiusMm = 10.3;
constexpr glm::dvec3 kCentreMm{0.37, -0.21, 0.13}; // from the box's centre

double distanceInside(int x, int y, int z) {
    const glm::dvec3 p = glm::dvec3(x, y, z) + 0.5 - 0.5 * kGrid - kCentreMm;
    return kRadiusMm - glm::length(p);
}

// Values: 100 everywhere (byLabel), or 100 * a smoothstep edge on the sphere.
Volume sphereValues(bool byLabel) {
    Volume v = Volume::allocate(glm::ivec3(kGrid), VoxelType::U8);
    auto* out = reinterpret_cast<std::uint8_t*>(v.data.data());
    for (int z = 0; z < kGrid; ++z)
        for (int y = 0; y < kGrid; ++y)
            for (int x = 0; x < kGrid; ++x) {
                const double t = std::clamp(distanceInside(x, y, z) / 1.5 + 0.5, 0.0, 1.0);
                out[v.index(x, y, z)] = static_cast<std::uint8_t>(
                    byLabel ? 100 : std::lround(100.0 * t * t * (3.0 - 2.0 * t)));
            }
    return v;
}

// Label 2 on the voxels whose centres lie in the sphere, 1 elsewhere.
Volume sphereLabels() {
    Volume v = Volume::allocate(glm::ivec3(kGrid), VoxelType::U8);
    auto* out = reinterpret_cast<std::uint8_t*>(v.data.data());
    for (int z = 0; z < kGrid; ++z)
        for (int y = 0; y < kGrid; ++y)
            for (int x = 0; x < kGrid; ++x)
                out[v.index(x, y, z)] = distanceInside(x, y, z) >= 0.0 ? 2 : 1;
    return v;
}

Scene sphereScene(bool byLabel, RenderMethod method) {
    const json opaque = {{{"value", 0}, {"color", {1, 1, 1}}, {"alpha", 0}},
                         {{"value", 40}, {"color", {1, 1, 1}}, {"alpha", 0}},
                         {{"value", 60}, {"color", {1, 1, 1}}, {"alpha", 1}}};
    const json clear = {{{"value", 0}, {"color", {1, 1, 1}}, {"alpha", 0}},
                        {{"value", 255}, {"color", {1, 1, 1}}, {"alpha", 0}}};
    json doc = {{"version", 1},
                {"volume", {{"phantom", "head"}, {"size", {8, 8, 8}}}},
                {"transfer", {{"points", byLabel ? clear : opaque}}},
                {"camera",
                 {{"projection", "orthographic"},
                  {"ortho_height", kViewMm},
                  {"look_at", {{"eye", {0, 0, 300}}, {"target", {0, 0, 0}}, {"up", {0, 1, 0}}}}}},
                {"lights", {{"ambient", 1.0}, {"headlight", 0.0}}},
                {"render",
                 {{"size", {kPixels, kPixels}},
                  {"background", "transparent"},
                  {"slice_spacing", 0.25},
                  {"method", method == RenderMethod::Raycast ? "raycast" : "slicing"}}}};
    if (byLabel) {
        // The scene needs a label source; render() gives sphereLabels instead.
        doc["labels"] = {{"phantom", true}};
        doc["transfer"]["labels"] = {{{"labels", {2}}, {"points", opaque}}};
    }
    return parseScene(doc, "/nonexistent", "label edge");
}

Image render(const gpu::Context& ctx, bool byLabel, RenderMethod method) {
    const Scene scene = sphereScene(byLabel, method);
    const Volume values = sphereValues(byLabel);
    bake::GradientBaker baker(ctx);
    render::GpuVolume gv = render::prepareVolume(
        ctx, baker, std::make_shared<Volume>(values), job::sceneWindow(scene, values), std::nullopt,
        byLabel ? std::make_shared<Volume>(sphereLabels()) : nullptr);
    render::VolumeRenderer renderer(ctx);
    return renderer.render(scene, gv);
}

double alphaAt(const Image& image, double x, double y) {
    // Bilinear over pixel centres (pixel i covers [i, i + 1)).
    const double fx = x - 0.5, fy = y - 0.5;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    auto a = [&](int i, int j) {
        i = std::clamp(i, 0, image.width - 1);
        j = std::clamp(j, 0, image.height - 1);
        return double(image.rgba[4 * (std::size_t(j) * image.width + i) + 3]);
    };
    const double tx = fx - x0, ty = fy - y0;
    return (1 - ty) * ((1 - tx) * a(x0, y0) + tx * a(x0 + 1, y0)) +
           ty * ((1 - tx) * a(x0, y0 + 1) + tx * a(x0 + 1, y0 + 1));
}

struct Silhouette {
    double radius = 0.0;   // the fitted circle's, pixels
    double residual = 0.0; // RMS distance of the contour from it, pixels
};

// The alpha = 0.5 contour along 720 rays from the alpha-weighted centroid,
// fitted with a circle (Kasa: least squares on x^2 + y^2 = a x + b y + c).
Silhouette silhouette(const Image& image) {
    double sx = 0, sy = 0, sw = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double a = image.rgba[4 * (std::size_t(y) * image.width + x) + 3];
            sx += a * (x + 0.5);
            sy += a * (y + 0.5);
            sw += a;
        }
    const double cx = sx / sw, cy = sy / sw;
    std::vector<glm::dvec2> contour;
    for (int i = 0; i < 720; ++i) {
        const double t = 2.0 * std::numbers::pi * i / 720.0;
        const glm::dvec2 d(std::cos(t), std::sin(t));
        double prev = alphaAt(image, cx, cy);
        for (double r = 0.05; r < 0.5 * image.width; r += 0.05) {
            const double a = alphaAt(image, cx + r * d.x, cy + r * d.y);
            if (prev >= 0.5 && a < 0.5) {
                const double back = 0.05 * (0.5 - a) / (prev - a);
                contour.push_back(glm::dvec2(cx, cy) + (r - back) * d);
                break;
            }
            prev = a;
        }
    }
    EXPECT_EQ(contour.size(), 720u) << "every ray must leave the sphere";
    glm::dmat3 m(0.0);
    glm::dvec3 rhs(0.0);
    for (const glm::dvec2& p : contour) {
        const glm::dvec3 row(p.x, p.y, 1.0);
        m += glm::outerProduct(row, row);
        rhs += row * glm::dot(p, p);
    }
    const glm::dvec3 abc = glm::inverse(m) * rhs;
    const glm::dvec2 centre = 0.5 * glm::dvec2(abc.x, abc.y);
    Silhouette s;
    s.radius = std::sqrt(abc.z + glm::dot(centre, centre));
    double squared = 0.0;
    for (const glm::dvec2& p : contour) {
        const double e = glm::length(p - centre) - s.radius;
        squared += e * e;
    }
    s.residual = std::sqrt(squared / double(contour.size()));
    return s;
}

class LabelEdge : public GpuTest {};

// Measured on lavapipe, both methods, in pixels of 0.25 mm (a voxel is 4):
// the labelled sphere 1.15 RMS off its circle, the one known by its values
// 0.19. The bound holds today's staircase; the fitted radii are the
// sphere's to 0.12 pixel.
TEST_F(LabelEdge, AHeldSpheresSilhouetteAgainstACircle) {
    const double radiusPx = kRadiusMm * kPixels / kViewMm;
    for (RenderMethod method : {RenderMethod::Slicing, RenderMethod::Raycast}) {
        const char* name = method == RenderMethod::Raycast ? "raycast" : "slicing";
        const Silhouette byLabel = silhouette(render(ctx(), true, method));
        const Silhouette byValue = silhouette(render(ctx(), false, method));
        std::printf("%s: labelled sphere %.3f px RMS off a circle of %.2f px (the sphere's "
                    "%.2f); the same by its values %.3f px off %.2f px\n",
                    name, byLabel.residual, byLabel.radius, radiusPx, byValue.residual,
                    byValue.radius);
        EXPECT_NEAR(byValue.radius, radiusPx, 0.5) << name;
        EXPECT_NEAR(byLabel.radius, radiusPx, 1.0) << name;
        EXPECT_LT(byLabel.residual, 1.25) << name;
        EXPECT_GT(byLabel.residual, 2.0 * byValue.residual) << name << ": control";
    }
}

} // namespace
} // namespace cutaway::test
