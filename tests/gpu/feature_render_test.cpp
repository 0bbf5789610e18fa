// Feature alignment rendered (paper section 4): with a surface- or
// segment-aligned operator the feature renders exactly as without the
// operator, while the same operator axis-aligned moves it; and classification
// by label colours each tissue by its own transfer function.
#include "bake/feature_bake.hpp"
#include "core/error.hpp"
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "render/feature_fields.hpp"
#include "scene/scene.hpp"
#include "volume/phantom.hpp"
#include "volume/segmentation.hpp"

#include <algorithm>
#include <array>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

using nlohmann::json;

// The head phantom (skin 1, skull 2, brain 3) seen from above, a peeler over
// its crown deep enough to reach the brain, and label classification. With
// `featureOnly` every tissue but the brain is transparent.
json featureHeadDocument(bool featureOnly) {
    json tissue = json::parse(R"([{"value": 0, "color": [0.9, 0.7, 0.6], "alpha": 0},
        {"value": 60, "color": [0.9, 0.7, 0.6], "alpha": 0.05},
        {"value": 200, "color": [1, 1, 0.9], "alpha": 0.8}])");
    json brain = json::parse(R"([{"value": 0, "color": [0.9, 0.5, 0.5], "alpha": 0},
        {"value": 100, "color": [0.9, 0.5, 0.5], "alpha": 0.3},
        {"value": 135, "color": [1.0, 0.8, 0.8], "alpha": 0.9}])");
    json none = json::parse(R"([{"value": 0, "color": [0, 0, 0], "alpha": 0},
        {"value": 255, "color": [0, 0, 0], "alpha": 0}])");
    json scene = {
        {"version", 1},
        {"volume", {{"phantom", "head"}, {"size", {64, 64, 64}}}},
        {"labels", {{"phantom", true}}},
        {"transfer",
         {{"points", featureOnly ? none : tissue},
          {"labels", {{{"labels", {"brain"}}, {"points", brain}}}}}},
        {"camera", {{"orbit", {{"azimuth", 20}, {"elevation", 60}, {"distance", 260}}}}},
        // Every sample (no early termination): the two renders' proxies reach
        // opacity at slightly different slices, and stopping there could
        // leave up to 1/255 behind in one and not the other.
        {"render",
         {{"size", {96, 96}},
          {"classification", "post"},
          {"background", "transparent"},
          {"termination_opacity", 1.0}}},
    };
    return scene;
}

json withPeeler(json scene, const json& alignment) {
    scene["operators"] = json::array({{
        {"type", "peeler"},
        {"placement", {{"translate", {0, 0, 16}}, {"scale", {50, 50, 30}}}},
        {"alignment", alignment},
        {"params", {{"hinge", -10}, {"thickness", 24}, {"radius", 4}, {"angle", 130}}},
    }});
    return scene;
}

Image render(const gpu::Context& ctx, const json& document) {
    return job::renderImage(ctx, parseScene(document, "/nonexistent", "test"));
}

class FeatureRender : public GpuTest {};

// The feature's pixels are those of the brain alone; every other tissue is
// transparent, so the images compare the feature only. Post-classification
// keeps each sample independent of its neighbour along the ray (a
// pre-integrated slab would also see what lies behind the feature's surface,
// and that moves). A fixed camera distance keeps the framing (a fit would grow with the
// operator's box). The tolerance allows for the two proxies' differently
// interpolated positions of the same slice points (float rounding).
constexpr float kTolerance = 2e-3f;

TEST_F(FeatureRender, FeatureRendersAsWithoutTheOperator) {
    const Image plain = render(ctx(), featureHeadDocument(true));
    double coverage = 0.0;
    for (std::size_t i = 3; i < plain.rgba.size(); i += 4)
        coverage += plain.rgba[i];
    ASSERT_GT(coverage, 300.0) << "the brain must be visible for the comparison to mean much";

    // Surface alignment: the brain must lie beyond tau + delta, where Eq. 9
    // leaves normals alone. Its least depth, from the CPU distance field:
    const Phantom phantom = makePhantom("head", glm::ivec3(64));
    const std::vector<float> dt = bake::distanceFieldCpu(objectMask(phantom.values, 30.0),
                                                         phantom.values.dims, glm::dvec3(1.0));
    float brainDepth = 1e9f;
    for (std::size_t i = 0; i < dt.size(); ++i)
        if (phantom.labels.raw(i) == 3) brainDepth = std::min(brainDepth, dt[i]);
    // Samples reach half a voxel beyond the brain's voxel centres: 1 mm margin.
    const double delta = 1.0, tau = brainDepth - 1.0 - delta;
    ASSERT_GT(tau, 0.5);
    const json aligned[] = {
        json{{"mode", "segment"}, {"labels", {"brain"}}, {"band", 2}},
        json{{"mode", "surface"}, {"threshold", 30}, {"depth", tau}, {"band", delta}},
    };
    for (const json& alignment : aligned) {
        const Image cut = render(ctx(), withPeeler(featureHeadDocument(true), alignment));
        expectAgree(plain, cut, kTolerance, alignment.dump());
    }
    // The same peel axis-aligned lifts the brain with the skin: the test can
    // fail, on any device (expectAgree).
    const Image axis = render(ctx(), withPeeler(featureHeadDocument(true), json{{"mode", "axis"}}));
    const ImageDiff lifted = compareImages(plain, axis);
    EXPECT_GT(lifted.maxAbs, 0.2f);
    EXPECT_GT(lifted.rms, 2.0 * kQuantizedRms);
}

// An operator that moves nothing (a retractor of opening 0) renders as no
// operator, surface-aligned too. Two things made its box show: Eq. 9 turned
// normals toward the distance field everywhere in the box, not only where
// material moves or is cut (0.34 here, up to 15/255 on ct_head), and a slab
// across the shell tau deep was lit at its front instead of its middle, a
// speckle (0.27 here). Pre-integrated and lit, both methods; the tolerance
// allows for the operator's proxy slicing the same points through other
// polygons.
TEST_F(FeatureRender, AnOperatorThatMovesNothingRendersAsNone) {
    json plain = featureHeadDocument(false);
    plain["render"]["classification"] = "preintegrated";
    plain["transfer"].erase("labels");
    // Not segment alignment: material that may move reads the scan without
    // the segment's values (operators.md), moved or not, so the skull's
    // partial-volume rim differs (by up to 0.19 here).
    const json alignments[] = {
        json{{"mode", "surface"}, {"threshold", 30}, {"depth", 2}, {"band", 2}},
    };
    for (const char* method : {"slicing", "raycast"}) {
        plain["render"]["method"] = method;
        const Image none = render(ctx(), plain);
        for (const json& alignment : alignments) {
            json still = plain;
            still["operators"] = json::array({{
                {"type", "retractor"},
                {"placement", {{"translate", {0, 0, 16}}, {"scale", {50, 50, 30}}}},
                {"alignment", alignment},
                {"params", {{"opening", 0}}},
            }});
            expectAgree(none, render(ctx(), still), 4e-3f,
                        std::string(method) + " " + alignment.dump());
        }
    }
}

TEST_F(FeatureRender, AlignedOperatorsStillMoveTheRest) {
    const Image plain = render(ctx(), featureHeadDocument(false));
    for (const json& alignment : {json{{"mode", "segment"}, {"labels", {"brain"}}},
                                  json{{"mode", "surface"}, {"threshold", 30}, {"depth", 1.5}}}) {
        const Image cut = render(ctx(), withPeeler(featureHeadDocument(false), alignment));
        EXPECT_GT(compareImages(plain, cut).rms, 0.02) << alignment.dump();
    }
}

TEST_F(FeatureRender, LabelsPickTheirTransferFunction) {
    // Brain-only classification shows only where the brain is; the same scene
    // with the brain's function applied to every label shows more.
    json brainOnly = featureHeadDocument(true);
    json everything = brainOnly;
    everything["transfer"]["points"] = brainOnly["transfer"]["labels"][0]["points"];
    const Image a = render(ctx(), brainOnly);
    const Image b = render(ctx(), everything);
    double alphaA = 0.0, alphaB = 0.0;
    for (std::size_t i = 3; i < a.rgba.size(); i += 4) {
        alphaA += a.rgba[i];
        alphaB += b.rgba[i];
        EXPECT_LE(a.rgba[i], b.rgba[i] + 1e-3f);
    }
    EXPECT_GT(alphaB, alphaA * 1.2);
}

} // namespace
} // namespace cutaway::test

namespace cutaway::test {
namespace {

class FeatureFieldsTest : public GpuTest {};

// The field an operator reads: the object above the threshold with its
// cavities filled (segmentation.hpp), its exact distance transform.
TEST_F(FeatureFieldsTest, SurfaceFieldIsTheDistanceToTheOutside) {
    const Phantom phantom = makePhantom("head", glm::ivec3(40));
    bake::GradientBaker baker(ctx());
    const render::GpuVolume volume =
        render::prepareVolume(ctx(), baker, std::make_shared<Volume>(phantom.values), {0.0, 255.0});
    render::FeatureFields fields(ctx());
    OperatorSpec spec;
    spec.alignment.mode = AlignmentMode::Surface;
    spec.alignment.threshold = 30.0;
    const gpu::Image& field = fields.fieldFor(spec, volume);
    const auto bytes = gpu::downloadImage(ctx(), field, bake::kFeatureLayout, 2);
    const std::vector<float> expected = bake::distanceFieldCpu(
        objectMask(phantom.values, 30.0), phantom.values.dims, glm::dvec3(1.0));
    const auto* halves = reinterpret_cast<const uint16_t*>(bytes.data());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const float w = glm::unpackHalf1x16(halves[i]);
        // Three passes store half floats, each within 2^-10 (feature_bake_test).
        ASSERT_NEAR(w, expected[i], 3.0f * expected[i] / 1024.0f + 1e-3f) << i;
    }
}

// A segment alignment's indicator streams from the labels or the scan into
// its texture: the field equals the bake of the indicator made whole on the
// host, and a segment without a voxel is bad input naming the operator.
TEST_F(FeatureFieldsTest, SegmentFieldIsTheMaskOfItsLabelsOrValues) {
    const Phantom phantom = makePhantom("head", glm::ivec3(40));
    bake::GradientBaker gradients(ctx());
    const render::GpuVolume volume =
        render::prepareVolume(ctx(), gradients, std::make_shared<Volume>(phantom.values),
                              {0.0, 255.0}, std::nullopt, std::make_shared<Volume>(phantom.labels));
    render::FeatureFields fields(ctx());
    const bake::FeatureBaker baker(ctx());
    const auto download = [&](const gpu::Image& image) {
        return gpu::downloadImage(ctx(), image, bake::kFeatureLayout, 2);
    };
    OperatorSpec spec;
    spec.name = "the peeler";
    spec.alignment.mode = AlignmentMode::Segment;
    spec.alignment.band = 2.0;
    for (const bool byRange : {false, true}) {
        SCOPED_TRACE(byRange ? "value range" : "labels");
        std::vector<std::uint8_t> indicator(phantom.values.voxelCount());
        if (byRange) {
            spec.alignment.range = std::array<double, 2>{100.0, 140.0};
            for (std::size_t i = 0; i < indicator.size(); ++i)
                indicator[i] = phantom.values.value(i) >= 100.0 && phantom.values.value(i) <= 140.0;
        } else {
            spec.alignment.labels = {3};
            for (std::size_t i = 0; i < indicator.size(); ++i)
                indicator[i] = phantom.labels.raw(i) == 3;
        }
        const std::size_t inside = std::count(indicator.begin(), indicator.end(), 1);
        ASSERT_GT(inside, 100u);
        ASSERT_LT(inside, indicator.size() / 2);
        const auto expected =
            download(baker.segmentMask(indicator, phantom.values.dims, glm::dvec3(1.0), 2.0));
        EXPECT_EQ(download(fields.fieldFor(spec, volume)), expected);
    }
    spec.alignment.range.reset();
    spec.alignment.labels = {9}; // no voxel has it
    try {
        fields.fieldFor(spec, volume);
        ADD_FAILURE() << "an empty segment must be refused";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("the peeler"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace cutaway::test
