// The ray caster with operators against slicing with its stencil pass: a ray
// takes an operator's slabs where its sample lies in the operator's deformed
// box and the untouched volume's elsewhere, resolving each point once (the
// back of a slab is the next one's front) where slicing resolves both ends.
// The samples are the same, so the images agree but for pixels whose sample
// lies on a box's face: rasterization decides those by the slice polygon's
// snapped edges, the rays by the box itself.
#include "core/error.hpp"
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"
#include "shared/operator_frame.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace cutaway::test {
namespace {

using nlohmann::json;

// The operator tests' phantom, closer up (the head fills the frame), every
// sample taken: each method stops a pixel at its own point past the
// termination opacity (a ray at once, slicing after its chunk of slices), and
// that difference (up to 1/255) is not what these tests compare.
json phantomScene() {
    json scene = operatorPhantomDocument();
    scene["camera"]["orbit"]["distance"] = 110;
    scene["render"]["size"] = {128, 128};
    scene["render"]["termination_opacity"] = 1.0;
    return scene;
}

// Each kind, placed where the close-up view of phantomScene() sees what it
// does (each changes 1 % of the image or more); the peeler's flap swings out
// of the volume's box, where only the operator's samples are.
const char* const kPeeler =
    R"({ "type": "peeler", "placement": { "translate": [0, 0, 16], "scale": [50, 50, 30] },
         "params": { "hinge": -10, "thickness": 12, "angle": 130 } })";
const char* const kRetractor =
    R"({ "type": "retractor", "placement": { "translate": [12, 12, 18], "scale": [20, 20, 20] },
         "params": { "opening": 10 } })";
const char* const kPliers =
    R"({ "type": "pliers", "placement": { "translate": [-10, -10, 12], "scale": [40, 40, 40] },
         "params": { "grasp": [0, 0, 10], "radius": 9, "displacement": [0, 0, 4] } })";
const char* const kDilator =
    R"({ "type": "dilator", "placement": { "translate": [14, -14, 14], "scale": [12, 12, 12] },
         "params": { "magnification": 2.0 } })";
// A smaller peeler, clear of kDilator.
const char* const kSmallPeeler =
    R"({ "type": "peeler", "placement": { "translate": [-13, 0, 22], "scale": [22, 36, 14] },
         "params": { "hinge": -8, "thickness": 6, "angle": 100 } })";
const char* const kSurface = R"({"mode": "surface", "threshold": 30, "depth": 3, "band": 2})";
const char* const kSegment = R"({"mode": "segment", "labels": ["brain"], "band": 2})";

json withOperators(std::initializer_list<std::pair<const char*, const char*>> ops) {
    json scene = phantomScene();
    scene["operators"] = json::array();
    for (const auto& [op, alignment] : ops) {
        json o = json::parse(op);
        if (alignment) o["alignment"] = json::parse(alignment);
        scene["operators"].push_back(o);
    }
    return scene;
}

class RaycastOperators : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        m_renderer = std::make_unique<job::FrameRenderer>(ctx());
    }
    void TearDown() override {
        m_renderer.reset();
        GpuTest::TearDown();
    }
    // One renderer for the test: the phantom is loaded and baked once, and
    // each frame switches method, operators or alignment from the one before.
    Image render(json document, const char* method) {
        document["render"]["method"] = method;
        return m_renderer->render(parseScene(document, "/nonexistent", "test"));
    }
    std::unique_ptr<job::FrameRenderer> m_renderer;
    // The share of pixels of `a` and `b` that differ by more than 2e-3.
    static double share(const Image& a, const Image& b) {
        std::size_t n = 0;
        for (std::size_t i = 0; i < a.rgba.size(); i += 4) {
            float e = 0.0f;
            for (std::size_t c = 0; c < 4; ++c)
                e = std::max(e, std::abs(a.rgba[i + c] - b.rgba[i + c]));
            n += e > 2e-3f;
        }
        return double(n) / double(a.rgba.size() / 4);
    }
    // Renders `scene` both ways and checks they agree: less than kFaceShare of
    // the pixels differ by more than the ray caster's tolerance without
    // operators (2e-3: rounding), and the mean
    // difference is small. Where the filter quantizes its weights the rounding
    // moves more pixels (up to 1.7 % on an H200): there the images agree as
    // expectAgree says. `castOut` receives the ray caster's image.
    void expectMatchesSlicing(const json& scene, const std::string& what,
                              Image* castOut = nullptr) {
        const Image sliced = render(scene, "slicing");
        const Image cast = render(scene, "raycast");
        if (castOut) *castOut = cast;
        if (!filtersInFloat()) {
            expectAgree(sliced, cast, 0.0f, what);
            return;
        }
        const ImageDiff d = compareImages(sliced, cast);
        EXPECT_LT(d.meanAbs, 1e-3) << what << ": max " << d.maxAbs;
        EXPECT_LT(share(sliced, cast), kFaceShare) << what;
    }
    // Measured: at most 0.04 % of the pixels in these scenes; on ct_head at 256^2
    // with a retractor, 0.1 %. An operator shaded with another's map or
    // alignment, or not at all, changes 2.5 % of the image or more.
    static constexpr double kFaceShare = 0.005;
};

TEST_F(RaycastOperators, MatchSlicingForEveryKindAndAlignment) {
    const Image untouched = render(phantomScene(), "raycast");
    for (const char* op : {kPeeler, kRetractor, kPliers, kDilator})
        for (const char* alignment : {static_cast<const char*>(nullptr), kSurface, kSegment}) {
            const json scene = withOperators({{op, alignment}});
            const std::string what =
                json::parse(op)["type"].get<std::string>() + " " + (alignment ? alignment : "axis");
            Image cast;
            expectMatchesSlicing(scene, what, &cast);
            EXPECT_GT(share(cast, untouched), 2.0 * kFaceShare)
                << what << ": the operator must show";
        }
}

TEST_F(RaycastOperators, MatchSlicingPostClassifiedAndWithLongSlabs) {
    json scene = withOperators({{kPeeler, kSurface}});
    scene["render"]["classification"] = "post";
    expectMatchesSlicing(scene, "post-classified");
    scene["render"]["classification"] = "preintegrated";
    scene["render"]["slice_spacing"] = 4.0;
    expectMatchesSlicing(scene, "d = 4");
    scene["camera"]["projection"] = "orthographic";
    expectMatchesSlicing(scene, "orthographic");
}

TEST_F(RaycastOperators, EachOperatorTakesItsOwnSlot) {
    // Three operators of different kinds and alignments, each of which shows
    // (the image without it differs): a slot reading another's map, uniforms
    // or alignment would change its region.
    json scene = withOperators(
        {{kSmallPeeler, kSegment},
         {kDilator, nullptr},
         {R"({ "type": "retractor", "placement": { "translate": [14, 12, 20], "scale": [14, 14, 14] },
               "params": { "opening": 10 } })",
          kSurface}});
    Image all;
    expectMatchesSlicing(scene, "peeler, dilator and retractor", &all);
    for (std::size_t i = 0; i < 3; ++i) {
        json without = scene;
        without["operators"].erase(i);
        EXPECT_GT(share(render(without, "raycast"), all), 2.0 * kFaceShare)
            << "operator " << i << " must show";
    }
    scene["operators"].erase(2);
    expectMatchesSlicing(scene, "peeler and dilator");
}

TEST_F(RaycastOperators, SequentialCompositionRaysTheLastOperator) {
    // The scan is resampled through the dilator on the CPU; the rays and the
    // slices see the result and the peeler alone.
    json scene = withOperators({{kDilator, nullptr}, {kPeeler, kSurface}});
    scene["render"]["operator_composition"] = "sequential";
    expectMatchesSlicing(scene, "sequential");
}

TEST_F(RaycastOperators, TheToleranceSeesAnOperatorGone) {
    // The comparisons above can fail, on any device (expectAgree): without
    // the operator, or with another alignment, far more pixels differ.
    const json peeled = withOperators({{kPeeler, kSurface}});
    const Image sliced = render(peeled, "slicing");
    for (const json& other : {phantomScene(), withOperators({{kPeeler, nullptr}})}) {
        const Image cast = render(other, "raycast");
        EXPECT_GT(share(cast, sliced), 5.0 * kFaceShare);
        EXPECT_GT(compareImages(cast, sliced).rms, 2.0 * kQuantizedRms);
    }
}

TEST_F(RaycastOperators, RefusesWhatOnlySlicingDraws) {
    const auto refusal = [](json scene) {
        scene["render"]["method"] = "raycast";
        try {
            parseScene(scene, "/nonexistent", "test");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    json four = withOperators({{kPliers, nullptr}, {kDilator, nullptr}, {kPeeler, nullptr}});
    EXPECT_EQ(refusal(four), "") << "three operators ray-cast";
    four["operators"].push_back(json::parse(
        R"({ "type": "dilator", "placement": { "translate": [-20, 0, -14], "scale": [10, 10, 10] }})"));
    const std::string tooMany = refusal(four);
    EXPECT_NE(tooMany.find("/render/method"), std::string::npos) << tooMany;
    EXPECT_NE(tooMany.find("at most " + std::to_string(CW_RAY_MAX_OPERATORS) + " operators"),
              std::string::npos)
        << tooMany;
    four["render"]["operator_composition"] = "sequential";
    EXPECT_EQ(refusal(four), "") << "under sequential composition only the last is live";
}

TEST_F(RaycastOperators, NameTheProxyOfEachPixelAsSlicingDoes) {
    // output.operator_id: the proxy of each pixel's first visible sample (-2
    // nothing, -1 the untouched volume, i operator i), the same but on the
    // boxes' faces.
    json scene = withOperators({{kSmallPeeler, kSurface}, {kDilator, nullptr}});
    scene["output"] = {{"operator_id", true}};
    const Image sliced = render(scene, "slicing");
    const Image cast = render(scene, "raycast");
    ASSERT_EQ(cast.operatorIds.size(), sliced.operatorIds.size());
    std::map<float, int> seen;
    std::size_t differing = 0;
    for (std::size_t p = 0; p < cast.operatorIds.size(); ++p) {
        ++seen[cast.operatorIds[p]];
        differing += cast.operatorIds[p] != sliced.operatorIds[p];
    }
    EXPECT_LT(double(differing) / double(cast.operatorIds.size()), kFaceShare);
    for (float id : {-2.0f, -1.0f, 0.0f, 1.0f})
        EXPECT_GT(seen[id], 100) << "pixels of id " << id
                                 << " (nothing, the volume, the operators)";
}

} // namespace
} // namespace cutaway::test
