// /operators in the scene: placement (Eq. 8) in both forms, parameters in
// millimetres converted to the operator's local frame.
#include "scene_test_util.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

OperatorSpec onlyOperator(const std::string& op) {
    const Scene s =
        parseScene(patched(R"({"operators": [)" + op + "]}"), "/nonexistent", "scene.json");
    EXPECT_EQ(s.operators.size(), 1u);
    return s.operators.at(0);
}

} // namespace

TEST(OperatorScene, MatrixAndTranslateRotateScaleAgree) {
    const OperatorSpec trs = onlyOperator(R"({ "type": "retractor",
        "placement": { "translate": [10, -20, 30], "rotate": [90, 0, 30], "scale": [40, 20, 10] } })");
    // The same map written out: T * Rz(30) * Ry(0) * Rx(90) * S(half sizes).
    glm::dmat4 a = glm::translate(glm::dmat4(1.0), glm::dvec3(10, -20, 30));
    a = glm::rotate(a, glm::radians(30.0), glm::dvec3(0, 0, 1));
    a = glm::rotate(a, glm::radians(90.0), glm::dvec3(1, 0, 0));
    a = glm::scale(a, glm::dvec3(20, 10, 5));
    std::string rows;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            if (!rows.empty()) rows += ',';
            rows += std::to_string(a[c][r]);
        }
    const OperatorSpec m =
        onlyOperator(R"({ "type": "retractor", "placement": { "matrix": [)" + rows + "] } }");
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(trs.localToWorld[c][r], a[c][r], 1e-9) << c << "," << r;
            EXPECT_NEAR(m.localToWorld[c][r], a[c][r], 1e-5) << c << "," << r;
        }
    // The local +z axis (toward the surface) goes to world -y after Rx(90), then Rz(30).
    const glm::dvec3 up = glm::normalize(glm::dvec3(trs.localToWorld[2]));
    EXPECT_NEAR(up.z, 0.0, 1e-12);
    EXPECT_NEAR(glm::length(up), 1.0, 1e-12);
    // Parameters in mm become local units of each axis: opening 8 mm across x (half size 20).
    const OperatorSpec r = onlyOperator(R"({ "type": "retractor",
        "placement": { "scale": [40, 20, 10] }, "params": { "length": 10, "depth": 4, "opening": 8 } })");
    EXPECT_FLOAT_EQ(r.params.a.x, 0.5f); // half length 5 mm / half y 10 mm
    EXPECT_FLOAT_EQ(r.params.a.y, 0.8f); // depth 4 mm / half z 5 mm
    EXPECT_FLOAT_EQ(r.params.a.z, 0.2f); // half opening 4 mm / half x 20 mm
}

TEST(OperatorScene, BadPlacementsAreReported) {
    EXPECT_NE(parseError(patched(R"({"operators": [{ "type": "pliers",
        "placement": { "matrix": [1,0,0,0, 0,1,0,0, 0,0,0,0, 0,0,0,1] } }]})"))
                  .find("/operators/0/placement/matrix: expected an invertible affine matrix"),
              std::string::npos);
    EXPECT_NE(parseError(patched(R"({"operators": [{ "type": "pliers",
        "placement": { "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "scale": [1, 1, 1] } }]})"))
                  .find("/operators/0/placement/scale: not allowed together with \"matrix\""),
              std::string::npos);
    EXPECT_NE(parseError(patched(R"({"operators": [{ "type": "pliers", "placement": {} }]})"))
                  .find("/operators/0/placement/scale"),
              std::string::npos);
    EXPECT_NE(
        parseError(
            patched(R"({"operators": [{ "type": "dilator", "placement": { "scale": [10, 10, 10] },
        "alignment": { "mode": "surface", "labels": [1] } }]})"))
            .find("/operators/0/alignment/labels: only with \"mode\": \"segment\""),
        std::string::npos);
}

TEST(OperatorScene, CutFaceIsForOperatorsThatCut) {
    const OperatorSpec op =
        onlyOperator(R"({ "type": "peeler", "placement": { "scale": [20, 20, 10] },
        "cut_face": { "color": [0.8, 0.2, 0.1], "mix": 0.5, "depth": 3 } })");
    ASSERT_TRUE(op.cutFace);
    EXPECT_EQ(op.cutFace->color, glm::vec3(0.8f, 0.2f, 0.1f));
    EXPECT_EQ(op.cutFace->mix, 0.5);
    EXPECT_EQ(op.cutFace->depth, 3.0);
    const OperatorSpec defaults = onlyOperator(R"({ "type": "retractor",
        "placement": { "scale": [20, 20, 10] }, "cut_face": { "color": [1, 1, 1] } })");
    ASSERT_TRUE(defaults.cutFace);
    EXPECT_EQ(defaults.cutFace->mix, 1.0);
    EXPECT_EQ(defaults.cutFace->depth, 1.0);
    EXPECT_FALSE(
        onlyOperator(R"({ "type": "peeler", "placement": { "scale": [9, 9, 9] } })").cutFace);
    // Pliers and dilators cut nothing: refused, naming why.
    for (const char* type : {"pliers", "dilator"})
        EXPECT_NE(parseError(patched(std::string(R"({"operators": [{ "type": ")") + type +
                                     R"(", "placement": { "scale": [9, 9, 9] },
            "cut_face": { "color": [1, 0, 0] } }]})"))
                      .find(std::string("/operators/0/cut_face: ") + type + " cut nothing"),
                  std::string::npos)
            << type;
    const std::pair<const char*, const char*> bad[] = {
        {R"({ "mix": 0.5 })", "/operators/0/cut_face/color"},
        {R"({ "color": [1, 0, 0], "mix": 1.01 })", "/operators/0/cut_face/mix"},
        {R"({ "color": [1, 0, 0], "depth": 0 })", "/operators/0/cut_face/depth"},
        {R"({ "color": [1, 0, 0], "colour": [1, 0, 0] })", "/operators/0/cut_face/colour"},
        {R"("red")", "/operators/0/cut_face"}};
    for (const auto& [face, pointer] : bad)
        EXPECT_NE(parseError(patched(std::string(R"({"operators": [{ "type": "peeler",
            "placement": { "scale": [9, 9, 9] }, "cut_face": )") +
                                     face + "}]}"))
                      .find(pointer),
                  std::string::npos)
            << face;
}

} // namespace cutaway::test
