// /camera/margin and /camera/zoom: with a margin, a fitted view frames the
// box's corners as the camera sees them, the margin kept free on each side;
// zoom scales a fitted view. An opaque box (every voxel visible) seen from
// an oblique orbit, in both projections, on a frame wider than high.
// Tolerance: 1.5 pixels (a sample's footprint at the silhouette).
#include "gpu_fixture.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <cstdio>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <optional>

namespace cutaway::test {
namespace {

constexpr int kWidth = 80, kHeight = 60;

// The columns and rows the opaque pixels span: (x0, y0, x1, y1), inclusive.
glm::ivec4 coverage(const Image& img) {
    glm::ivec4 r(img.width, img.height, -1, -1);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (img.rgba[4 * std::size_t(y * img.width + x) + 3] > 0.5f)
                r = glm::ivec4(std::min(r.x, x), std::min(r.y, y), std::max(r.z, x),
                               std::max(r.w, y));
    return r;
}

// How far the opaque pixels keep from the frame's edges, in fractions of
// the width (left, right) and height (top, bottom): the smallest of each pair.
glm::dvec2 freeFraction(const glm::ivec4& r) {
    return {std::min(r.x, kWidth - 1 - r.z) / double(kWidth),
            std::min(r.y, kHeight - 1 - r.w) / double(kHeight)};
}

class Framing : public GpuTest {
protected:
    Image render(bool ortho, std::optional<double> margin, double zoom = 1.0) {
        nlohmann::json camera = {{"projection", ortho ? "orthographic" : "perspective"},
                                 {"orbit", {{"azimuth", 35}, {"elevation", 25}}}};
        if (margin) camera["margin"] = *margin;
        if (zoom != 1.0) camera["zoom"] = zoom;
        const nlohmann::json doc = {
            {"version", 1},
            {"volume", {{"phantom", "head"}, {"size", {8, 8, 8}}}},
            {"transfer",
             {{"points",
               {{{"value", 0}, {"color", {1, 1, 1}}, {"alpha", 1}},
                {{"value", 255}, {"color", {1, 1, 1}}, {"alpha", 1}}}}}},
            {"camera", camera},
            {"render", {{"size", {kWidth, kHeight}}, {"background", "transparent"}}}};
        Volume box = Volume::allocate(glm::ivec3(40, 24, 16), VoxelType::U8);
        std::fill(box.data.begin(), box.data.end(), std::byte{100});
        return renderVolume(ctx(), parseScene(doc, "/nonexistent", "framing"), box);
    }
};

TEST_F(Framing, AMarginKeepsItsShareOfTheFrameFreeAndZoomScales) {
    for (bool ortho : {false, true}) {
        SCOPED_TRACE(ortho ? "orthographic" : "perspective");
        const glm::ivec4 sphere = coverage(render(ortho, std::nullopt));
        for (double margin : {0.0, 0.1, 0.25}) {
            SCOPED_TRACE(margin);
            const glm::ivec4 r = coverage(render(ortho, margin));
            const glm::dvec2 free = freeFraction(r);
            std::printf("margin %.2f: free %.3f x %.3f\n", margin, free.x, free.y);
            // Every side keeps the margin; the tighter axis meets it.
            EXPECT_GE(free.x, margin - 1.5 / kWidth) << r.x << " " << r.z;
            EXPECT_GE(free.y, margin - 1.5 / kHeight) << r.y << " " << r.w;
            EXPECT_TRUE(free.x < margin + 1.5 / kWidth || free.y < margin + 1.5 / kHeight)
                << "the box fills the frame up to the margin";
        }
        // Control: the bounding sphere's fit leaves more of the frame free.
        const glm::dvec2 loose = freeFraction(sphere);
        std::printf("sphere fit: free %.3f x %.3f\n", loose.x, loose.y);
        EXPECT_GT(std::min(loose.x, loose.y), 0.1);
        // Zoom 2 on a margin of 0.25: the box twice as large, up to the edges.
        const glm::ivec4 half = coverage(render(ortho, 0.25)),
                         whole = coverage(render(ortho, 0.25, 2.0));
        EXPECT_NEAR(double(whole.z - whole.x), 2.0 * (half.z - half.x), ortho ? 2.0 : 8.0);
    }
}

TEST(FramingScene, MarginAndZoomNeedAFittedView) {
    const auto error = [](const nlohmann::json& camera) {
        const nlohmann::json doc = {
            {"version", 1}, {"volume", {{"phantom", "head"}}}, {"camera", camera}};
        try {
            parseScene(doc, "/nonexistent", "s");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(error({{"margin", 0.1}, {"zoom", 2}}), "") << "control: an orbit that fits";
    EXPECT_NE(error({{"margin", 0.1}, {"orbit", {{"distance", 300}}}}).find("/camera/margin"),
              std::string::npos);
    EXPECT_NE(error({{"zoom", 2}, {"look_at", {{"eye", {0, -300, 0}}}}}).find("/camera/zoom"),
              std::string::npos);
    EXPECT_NE(error({{"margin", 0.5}}).find("/camera/margin"), std::string::npos);
}

} // namespace
} // namespace cutaway::test
