// Parsing of /meshes (glTF tool models) and /operators/N/glyph.
#include "scene/scene.hpp"
#include "scene_test_util.hpp"

#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

using nlohmann::json;

const char* kOperator = R"({"type": "retractor", "placement": {"scale": [40, 40, 20]}})";

class MeshScene : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir.write("tool.glb", "not read when parsing");
        m_dir.write("tool.obj", "wrong kind");
    }
    json withMeshes(const std::string& meshes, bool withOperator = true) const {
        json doc = minimalScene();
        doc["meshes"] = json::parse(meshes);
        if (withOperator) doc["operators"] = json::array({json::parse(kOperator)});
        return doc;
    }
    Scene parse(const json& doc) const { return parseScene(doc, m_dir.path(), "scene.json"); }
    std::string error(const json& doc) const { return parseError(doc, m_dir.path()); }
    TempDir m_dir;
};

TEST_F(MeshScene, PlacementDefaultsToMetresInTheWorld) {
    const Scene s = parse(withMeshes(R"([{"file": "tool.glb"}])"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const MeshSpec& m = s.meshes[0];
    EXPECT_EQ(m.file, (m_dir.path() / "tool.glb").lexically_normal());
    EXPECT_EQ(m.name, "mesh 0");
    EXPECT_FALSE(m.attach);
    EXPECT_FALSE(m.color);
    // 0.1 m along x is 100 mm.
    EXPECT_EQ(glm::dvec3(m.placement * glm::dvec4(0.1, 0, 0, 1)), glm::dvec3(100, 0, 0));
}

TEST_F(MeshScene, PlacementComposesTranslateRotateScaleAndUnits) {
    const Scene s = parse(withMeshes(R"([{"file": "tool.glb", "color": [1, 0, 0], "attach": 0,
        "placement": {"translate": [1, 2, 3], "rotate": [0, 0, 90], "scale": 2, "units": "mm"}}])"));
    const MeshSpec& m = s.meshes[0];
    ASSERT_TRUE(m.attach);
    EXPECT_EQ(*m.attach, 0);
    EXPECT_EQ(*m.color, glm::vec3(1, 0, 0));
    // x -> 2 x, rotated 90 degrees about z -> +y, then translated.
    const glm::dvec3 p(m.placement * glm::dvec4(1, 0, 0, 1));
    EXPECT_NEAR(p.x, 1.0, 1e-12);
    EXPECT_NEAR(p.y, 4.0, 1e-12);
    EXPECT_NEAR(p.z, 3.0, 1e-12);
    const Scene v =
        parse(withMeshes(R"([{"file": "tool.glb", "placement": {"scale": [1, 2, 3]}}])"));
    EXPECT_EQ(glm::dvec3(v.meshes[0].placement * glm::dvec4(1, 1, 1, 1)),
              glm::dvec3(1000, 2000, 3000));
}

TEST_F(MeshScene, BadMeshesAreReportedWithTheirPointers) {
    EXPECT_EQ(error(withMeshes(R"([{"file": "tool.glb", "attach": 1}])")),
              "scene.json: /meshes/0/attach: expected an integer in [0, 0], got 1");
    EXPECT_EQ(error(withMeshes(R"([{"file": "tool.glb", "attach": 0}])", false)),
              "scene.json: /meshes/0/attach: there are no operators to attach to");
    EXPECT_EQ(error(withMeshes(R"([{"file": "tool.glb", "attach": "x"}])", false)),
              "scene.json: /meshes/0/attach: expected an integer in [0, 2147483647], got \"x\"");
    EXPECT_EQ(error(withMeshes(R"([{"file": "tool.obj"}])")),
              "scene.json: /meshes/0/file: expected a glTF 2.0 model (.gltf or .glb), got "
              "\"tool.obj\"");
    EXPECT_EQ(error(withMeshes(R"([{}])")),
              "scene.json: /meshes/0/file: missing: expected a .gltf or .glb file");
    EXPECT_NE(error(withMeshes(R"([{"file": "absent.glb"}])")).find("/meshes/0/file: no such file"),
              std::string::npos);
    EXPECT_EQ(error(withMeshes(R"([{"file": "tool.glb", "placement": {"units": "cm"}}])")),
              "scene.json: /meshes/0/placement/units: expected one of \"m\", \"mm\", got "
              "\"cm\"");
    EXPECT_EQ(error(withMeshes(R"([{"file": "tool.glb", "placement": {"scale": 0}}])")),
              "scene.json: /meshes/0/placement/scale: expected a number in (0, 10000], got 0");
    EXPECT_EQ(error(withMeshes(R"([{"file": "tool.glb", "colour": [1, 0, 0]}])")),
              "scene.json: /meshes/0/colour: unknown key (did you mean \"color\"?)");
    EXPECT_EQ(error(withMeshes(R"({"file": "tool.glb"})")),
              "scene.json: /meshes: expected an array of at most 16 objects, got "
              "{\"file\":\"tool.glb\"}");
}

TEST_F(MeshScene, GlyphIsABooleanOrAnObject) {
    json doc = minimalScene();
    doc["operators"] = json::array({json::parse(kOperator), json::parse(kOperator)});
    doc["operators"][0]["glyph"] = true;
    doc["operators"][1]["glyph"] = json::parse(R"({"color": [0, 1, 0], "width": 2})");
    const Scene s = parse(doc);
    EXPECT_TRUE(s.operators[0].glyph.enabled);
    EXPECT_EQ(s.operators[0].glyph.width, 0.0); // automatic
    EXPECT_TRUE(s.operators[1].glyph.enabled);
    EXPECT_EQ(s.operators[1].glyph.color, glm::vec3(0, 1, 0));
    EXPECT_EQ(s.operators[1].glyph.width, 2.0);
    doc["operators"][1]["glyph"] = json::parse(R"({"show": false})");
    EXPECT_FALSE(parse(doc).operators[1].glyph.enabled);
    doc["operators"][1]["glyph"] = "yes";
    EXPECT_EQ(error(doc), "scene.json: /operators/1/glyph: expected true, false or an object, got "
                          "\"yes\"");
    doc["operators"][1]["glyph"] = json::parse(R"({"width": -1, "colour": 1})");
    const auto problems = lines(error(doc));
    ASSERT_EQ(problems.size(), 2u) << error(doc);
}

} // namespace
} // namespace cutaway::test
