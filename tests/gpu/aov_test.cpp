// The channels beyond colour (/output/aovs, /output/mattes; docs/compositing.md),
// checked against the colour image and against geometry known in closed form,
// for slicing and the ray caster alike: "Z" is finite exactly where the first
// visible sample is (the operator_id channel's threshold), grows away from the
// eye as the distance to a tilted plane does, and names the point where the
// label channel's label lies; the mattes of every label add up to alpha.
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"
#include "volume/phantom.hpp"
#include "volume/volume.hpp"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

namespace cutaway::test {
namespace {

using nlohmann::json;

constexpr const char* kMethods[] = {"slicing", "raycast"};

// The ray through the centre of pixel (x, y) of a square `size` image, for a
// camera at `eye` looking along -z with +y up: its unit direction.
glm::dvec3 rayThrough(int x, int y, int size, double fovDeg) {
    const double t = std::tan(fovDeg * std::numbers::pi / 360.0);
    const double u = ((x + 0.5) / size * 2.0 - 1.0) * t, v = (1.0 - (y + 0.5) / size * 2.0) * t;
    return glm::normalize(glm::dvec3(u, v, -1.0));
}

class AovTest : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        m_renderer = std::make_unique<job::FrameRenderer>(ctx());
    }
    void TearDown() override {
        m_renderer.reset();
        GpuTest::TearDown();
    }
    Image render(json document, const char* method) {
        document["render"]["method"] = method;
        return m_renderer->render(parseScene(document, "/nonexistent", "test"));
    }
    std::unique_ptr<job::FrameRenderer> m_renderer;
};

TEST_F(AovTest, DepthIsFiniteExactlyWhereTheFirstVisibleSampleIs) {
    for (const json& operators : phantomOperatorCases()) {
        for (const char* method : kMethods) {
            SCOPED_TRACE(std::string(method) + " " + operators.dump());
            json doc = operatorPhantomDocument();
            doc["operators"] = operators;
            const Image plain = render(doc, method);
            doc["output"]["aovs"] = {"Z", "operator_id"};
            const Image img = render(doc, method);
            EXPECT_EQ(img.rgba, plain.rgba) << "the channels must not change the picture";
            ASSERT_EQ(img.depth.size(), img.operatorIds.size());
            ASSERT_EQ(img.depth.size(), std::size_t(img.width * img.height));
            int finite = 0, mismatched = 0;
            for (std::size_t p = 0; p < img.depth.size(); ++p) {
                const float z = img.depth[p];
                const bool seen = img.operatorIds[p] != -2.0f;
                mismatched += std::isfinite(z) != seen;
                if (!std::isfinite(z)) {
                    EXPECT_EQ(z, INFINITY) << "nothing visible is +infinity, not NaN";
                    continue;
                }
                ++finite;
                // Alpha below the threshold's share means nothing reached it.
                EXPECT_GE(img.rgba[4 * p + 3], 0.005f) << p;
            }
            EXPECT_EQ(mismatched, 0);
            // Control: the image has both (the head, and the corners around it).
            EXPECT_GT(finite, 1000);
            EXPECT_LT(finite, int(img.depth.size()) - 500);
        }
    }
}

// 64^3 voxels of 1 mm, value 200 under the plane z = 0.3 x (world, the
// volume's centre at 0: voxel i at i - 31.5), 0 above it.
Volume tiltedHalfSpace() {
    Volume v = Volume::allocate(glm::ivec3(64), VoxelType::U8, glm::dvec3(1.0));
    for (int z = 0; z < 64; ++z)
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x)
                if (z - 31.5 < 0.3 * (x - 31.5)) v.data[v.index(x, y, z)] = std::byte{200};
    return v;
}

constexpr int kPlaneSize = 40;
constexpr double kEyeHeight = 200.0;

Scene planeScene(const char* method, bool perspective) {
    const json doc = {
        {"version", 1},
        {"volume", {{"phantom", "head"}, {"size", {8, 8, 8}}}},
        {"transfer",
         {{"points",
           {{{"value", 0}, {"color", {1, 1, 1}}, {"alpha", 0}},
            {{"value", 60}, {"color", {1, 1, 1}}, {"alpha", 0}},
            {{"value", 200}, {"color", {0.9, 0.85, 0.8}}, {"alpha", 1}}}}}},
        {"camera",
         {{"projection", perspective ? "perspective" : "orthographic"},
          {"ortho_height", 40},
          {"fov", 10},
          {"look_at", {{"eye", {0, 0, kEyeHeight}}, {"target", {0, 0, 0}}, {"up", {0, 1, 0}}}}}},
        {"render",
         {{"size", {kPlaneSize, kPlaneSize}}, {"background", "transparent"}, {"method", method}}},
        {"output", {{"aovs", {"Z"}}}}};
    return parseScene(doc, "/nonexistent", "tilted plane");
}

TEST_F(AovTest, DepthIsThePlanarDepthOfATiltedPlane) {
    // 0.6 voxel: the plane is stored as a staircase of 1 mm voxels, whose
    // reconstructed surface itself strays about half a voxel from the plane
    // (perspective measured 0.56 mm, orthographic under 0.5).
    constexpr double kBound = 0.6;
    const Volume volume = tiltedHalfSpace();
    for (const char* method : kMethods) {
        SCOPED_TRACE(method);
        // Orthographic: Z = 200 - z on the surface, z = 0.3 x + c, where c (a
        // fraction of a voxel) is where the transfer function's threshold lies
        // across the step. The fit must find the slope, and every pixel lie on it.
        const Image ortho = renderVolume(ctx(), planeScene(method, false), volume);
        double sx = 0, sz = 0, sxx = 0, sxz = 0;
        int n = 0;
        for (int y = 0; y < kPlaneSize; ++y)
            for (int x = 0; x < kPlaneSize; ++x) {
                const float z = ortho.depth[std::size_t(y * kPlaneSize + x)];
                ASSERT_TRUE(std::isfinite(z)) << x << "," << y;
                const double wx = (x + 0.5) - kPlaneSize / 2.0; // 1 mm per pixel
                sx += wx, sz += z, sxx += wx * wx, sxz += wx * z, ++n;
            }
        const double slope = (n * sxz - sx * sz) / (n * sxx - sx * sx);
        const double offset = (sz - slope * sx) / n;
        EXPECT_NEAR(slope, -0.3, 0.01) << "Z falls where the plane rises towards the eye";
        EXPECT_NEAR(offset, kEyeHeight, 1.0);
        const double c = kEyeHeight - offset;
        double worst = 0.0;
        for (int y = 0; y < kPlaneSize; ++y)
            for (int x = 0; x < kPlaneSize; ++x) {
                const double wx = (x + 0.5) - kPlaneSize / 2.0;
                const double expected = kEyeHeight - (0.3 * wx + c);
                worst = std::max(worst,
                                 std::abs(ortho.depth[std::size_t(y * kPlaneSize + x)] - expected));
            }
        EXPECT_LT(worst, kBound) << "mm off the plane";
        std::printf("%s orthographic: worst %.3f mm\n", method, worst);

        // Perspective: Z is the planar depth t * (d . view), not the distance t
        // along the ray, which is up to 0.8 % longer in this view's corners
        // (1.5 mm at 200 mm): the control shows the bound tells them apart.
        const Image persp = renderVolume(ctx(), planeScene(method, true), volume);
        // The residuals against both, each less its mean: where the threshold
        // lies across the step may differ by a fraction of a spacing here.
        std::vector<double> planar, alongRay;
        for (int y = 0; y < kPlaneSize; ++y)
            for (int x = 0; x < kPlaneSize; ++x) {
                const glm::dvec3 d = rayThrough(x, y, kPlaneSize, 10.0);
                // eye + t d on z = 0.3 x + c: 200 + t dz = 0.3 t dx + c.
                const double t = (c - kEyeHeight) / (d.z - 0.3 * d.x);
                const double z = persp.depth[std::size_t(y * kPlaneSize + x)];
                planar.push_back(z - t * -d.z);
                alongRay.push_back(z - t);
            }
        const auto spread = [](const std::vector<double>& r, double& mean) {
            mean = std::accumulate(r.begin(), r.end(), 0.0) / double(r.size());
            double most = 0.0;
            for (double v : r)
                most = std::max(most, std::abs(v - mean));
            return most;
        };
        double bias = 0.0, rayBias = 0.0;
        worst = spread(planar, bias);
        const double worstAlongRay = spread(alongRay, rayBias);
        EXPECT_LT(std::abs(bias), kBound) << "mm between the projections' surfaces";
        EXPECT_LT(worst, kBound) << "mm off the planar depth";
        std::printf("%s perspective: worst %.3f mm, along the ray %.3f\n", method, worst,
                    worstAlongRay);
        EXPECT_GT(worstAlongRay, kBound) << "control: the distance along the ray is not Z";
    }
}

// The label channel, checked through Z: the point at distance Z along each
// pixel's ray lies on the first visible sample, so the phantom's label there
// (or one voxel before or after it along the ray: the label volume is read at
// the nearest voxel and a surface lies between two) is the channel's label.
TEST_F(AovTest, LabelIsThePhantomsLabelWhereDepthPutsTheFirstVisibleSample) {
    const Phantom phantom = makePhantom("head", glm::ivec3(64));
    const auto labelAt = [&](glm::dvec3 p) {
        const glm::ivec3 i(glm::floor(p + 32.0));
        if (glm::any(glm::lessThan(i, glm::ivec3(0))) ||
            glm::any(glm::greaterThan(i, glm::ivec3(63))))
            return 0;
        return int(std::to_integer<int>(phantom.labels.data[phantom.labels.index(i.x, i.y, i.z)]));
    };
    const json cases = {json::array(), phantomOperatorCases()[2]}; // the retractor opens the brain
    for (const json& operators : cases) {
        for (const char* method : kMethods) {
            SCOPED_TRACE(std::string(method) + " " + operators.dump());
            json doc = operatorPhantomDocument();
            doc["operators"] = operators;
            doc["camera"] = {
                {"fov", 20},
                {"look_at", {{"eye", {0, 0, 260}}, {"target", {0, 0, 0}}, {"up", {0, 1, 0}}}}};
            doc["output"]["aovs"] = {"Z", "label", "operator_id"};
            const Image img = render(doc, method);
            ASSERT_EQ(img.labelIds.size(), std::size_t(img.width * img.height));
            std::map<int, int> seen;
            int checked = 0, agreeing = 0;
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < img.width; ++x) {
                    const std::size_t p = std::size_t(y * img.width + x);
                    const float label = img.labelIds[p];
                    ++seen[int(label)];
                    if (!std::isfinite(img.depth[p])) {
                        EXPECT_EQ(label, 0.0f) << "nothing visible: " << x << "," << y;
                        continue;
                    }
                    // What an operator moved came from elsewhere: its label is
                    // not the one at the point where it now lies.
                    if (img.operatorIds[p] != -1.0f) continue;
                    const glm::dvec3 d = rayThrough(x, y, img.width, 20.0);
                    const glm::dvec3 hit = glm::dvec3(0, 0, 260) + double(img.depth[p]) * d;
                    ++checked;
                    for (double step : {-1.0, 0.0, 1.0})
                        if (labelAt(hit + step * d) == int(label)) {
                            ++agreeing;
                            break;
                        }
                }
            EXPECT_GT(checked, 1000);
            EXPECT_GE(agreeing, checked * 98 / 100) << "of " << checked << " pixels";
            EXPECT_GT(seen[1], 500) << "skin, seen from above";
            if (!operators.empty()) {
                EXPECT_GT(seen[3], 30) << "the brain in the opening";
            }
        }
    }
}

TEST_F(AovTest, MattesOfEveryLabelAddUpToAlpha) {
    for (const json& operators : phantomOperatorCases()) {
        std::vector<Image> methods;
        for (const char* method : kMethods) {
            SCOPED_TRACE(std::string(method) + " " + operators.dump());
            json doc = operatorPhantomDocument();
            doc["operators"] = operators;
            doc["render"]["samples"] = 2; // mattes are averaged over the passes, as colour is
            const Image plain = render(doc, method);
            doc["output"]["mattes"] = {"background", "skin", "skull", "brain"};
            const Image img = render(doc, method);
            EXPECT_EQ(img.rgba, plain.rgba) << "the mattes must not change the picture";
            ASSERT_EQ(img.mattes.size(), 4u);
            EXPECT_EQ(img.mattes[2].name, "matte.skull");
            double worstSum = 0.0, worstOver = 0.0, brain = 0.0;
            for (std::size_t p = 0; p < img.mattes[0].values.size(); ++p) {
                const double alpha = img.rgba[4 * p + 3];
                double sum = 0.0;
                for (const ImageChannel& m : img.mattes) {
                    EXPECT_GE(m.values[p], 0.0f);
                    worstOver = std::max(worstOver, m.values[p] - alpha);
                    sum += m.values[p];
                }
                worstSum = std::max(worstSum, std::abs(sum - alpha));
                brain += img.mattes[3].values[p];
            }
            EXPECT_LT(worstSum, 2e-3) << "the labels share each pixel's alpha between them";
            EXPECT_LT(worstOver, 1e-4);
            EXPECT_GT(brain, 5.0) << "the brain shows through the translucent skin";
            methods.push_back(img);
        }
        // Both methods share the brain's pixels between the labels alike.
        double rms = 0.0;
        for (std::size_t m = 0; m < 4; ++m)
            for (std::size_t p = 0; p < methods[0].mattes[m].values.size(); ++p) {
                const double e = methods[0].mattes[m].values[p] - methods[1].mattes[m].values[p];
                rms += e * e;
            }
        const double count = 4.0 * double(methods[0].mattes[0].values.size());
        EXPECT_LT(std::sqrt(rms / count), 0.02);
    }
}

} // namespace
} // namespace cutaway::test
