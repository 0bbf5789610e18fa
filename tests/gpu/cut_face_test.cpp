// /operators/N/cut_face (operator_sample.h's cutFaceShare): the faces a
// peeler or a retractor cuts take the given colour, only inside the
// operator's proxies, in both methods alike; mix 0 leaves the picture as it
// was to the bit. Controls: the same scene without cut_face has (almost) no
// pixel of the colour; the untouched volume's pixels do not change.
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

class CutFace : public GpuTest {};

using nlohmann::json;

Image render(const gpu::Context& ctx, const json& document) {
    return job::renderImage(ctx, parseScene(document, "/nonexistent", "test"));
}

// The operator phantom's peeler and retractor (phantomOperatorCases), with
// the operator ids written, its cut faces coloured pure green (a colour
// the head's transfer function never takes) when `face` is given.
json sceneWith(const json& operators, const json& face, const char* method = "slicing") {
    json doc = operatorPhantomDocument();
    doc["operators"] = operators;
    if (!face.is_null()) doc["operators"][0]["cut_face"] = face;
    doc["render"]["method"] = method;
    doc["output"]["operator_id"] = true;
    return doc;
}

// Pixels whose green stands out from red and blue by half the pixel's alpha.
int greenPixels(const Image& image) {
    int count = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4)
        if (image.rgba[i + 1] - std::max(image.rgba[i], image.rgba[i + 2]) >
            0.5f * image.rgba[i + 3])
            ++count;
    return count;
}

TEST_F(CutFace, ColoursTheCutFacesInsideTheOperatorOnly) {
    const json green = {{"color", {0.0, 1.0, 0.0}}, {"mix", 1.0}, {"depth", 3.0}};
    for (std::size_t c = 1; c < phantomOperatorCases().size(); ++c) {
        const json operators = phantomOperatorCases()[c];
        SCOPED_TRACE(operators[0]["type"].get<std::string>());
        const Image plain = render(ctx(), sceneWith(operators, nullptr));
        const Image faced = render(ctx(), sceneWith(operators, green));
        // Measured on lavapipe (96 x 96): 0 green pixels without; with, 341
        // (the peeler: the flap's underside and the bed under it) and 80
        // (the retractor: the incision's walls).
        EXPECT_EQ(greenPixels(plain), 0);
        EXPECT_GT(greenPixels(faced), 40);
        // Only the operator's proxies change: a pixel that changes visibly
        // (by 0.05 or more) is one whose first visible sample is the
        // operator's (id 0), or whose only samples are faint (-2) or lie
        // behind the untouched volume's translucent skin (-1), both rare
        // (measured: 530 of 541 and 160 of 160 pixels are the operator's).
        ASSERT_EQ(faced.operatorIds.size(), std::size_t(faced.width) * faced.height);
        int changed = 0, inOperator = 0;
        for (std::size_t p = 0; p < faced.operatorIds.size(); ++p) {
            float change = 0.0f;
            for (int k = 0; k < 4; ++k)
                change = std::max(change, std::abs(faced.rgba[4 * p + k] - plain.rgba[4 * p + k]));
            if (change < 0.05f) continue;
            ++changed;
            inOperator += faced.operatorIds[p] == 0.0f;
        }
        EXPECT_GT(changed, 40);
        EXPECT_GE(inOperator, changed * 9 / 10);
        // Mix 0: the data's own colour, to the bit.
        json none = green;
        none["mix"] = 0.0;
        const Image mixed0 = render(ctx(), sceneWith(operators, none));
        EXPECT_EQ(mixed0.rgba, plain.rgba);
    }
}

TEST_F(CutFace, BothMethodsColourTheSameFaces) {
    const json red = {{"color", {0.9, 0.1, 0.1}}, {"mix", 0.8}, {"depth", 2.0}};
    for (std::size_t c = 1; c < phantomOperatorCases().size(); ++c) {
        const json operators = phantomOperatorCases()[c];
        json sliced = sceneWith(operators, red, "slicing");
        json cast = sceneWith(operators, red, "raycast");
        sliced["render"]["termination_opacity"] = 1.0;
        cast["render"]["termination_opacity"] = 1.0;
        const Image a = render(ctx(), sliced);
        const Image b = render(ctx(), cast);
        // The bound of tests/gpu/raycast_operators_test.cpp.
        if (!filtersInFloat()) {
            expectAgree(a, b, 0.0f, operators.dump());
            continue;
        }
        EXPECT_LT(compareImages(a, b).meanAbs, 1e-3) << operators.dump();
    }
}

} // namespace
} // namespace cutaway::test
