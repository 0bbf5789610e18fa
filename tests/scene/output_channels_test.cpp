// /output/aovs and /output/mattes (scene_parser.cpp): the EXR channels beyond
// colour. Each refusal names its JSON pointer; the accepted forms fill
// OutputSettings, the old /output/operator_id key as an alias.
#include "scene_test_util.hpp"

#include <gtest/gtest.h>
#include <string>

namespace cutaway::test {
namespace {

constexpr const char* kLabels = R"({"labels": {"phantom": true}})";

Scene parsed(const nlohmann::json& document) {
    return parseScene(document, "/nonexistent/scenes", "scene.json");
}

nlohmann::json withLabels(const std::string& output) {
    nlohmann::json document = patched(kLabels);
    document["output"] = nlohmann::json::parse(output);
    return document;
}

bool mentions(const std::string& message, const std::string& part) {
    return message.find(part) != std::string::npos;
}

TEST(OutputChannels, ReadsAovsAndMattes) {
    const Scene none = parsed(withLabels("{}"));
    EXPECT_FALSE(none.output.anyAov());

    const Scene s =
        parsed(withLabels(R"({"aovs": ["Z", "label", "operator_id"], "mattes": ["brain", 2]})"));
    EXPECT_TRUE(s.output.depth);
    EXPECT_TRUE(s.output.labelId);
    EXPECT_TRUE(s.output.operatorId);
    ASSERT_EQ(s.output.mattes.size(), 2u);
    EXPECT_EQ(s.output.mattes[0].channel, "matte.brain");
    EXPECT_EQ(s.output.mattes[0].id, 3);
    EXPECT_EQ(s.output.mattes[1].channel, "matte.2");
    EXPECT_EQ(s.output.mattes[1].id, 2);
    EXPECT_TRUE(s.output.labelAovs());

    // Z alone needs no labels; the old key is an alias of "operator_id".
    const Scene z = parsed(patched(R"({"output": {"aovs": ["Z"]}})"));
    EXPECT_TRUE(z.output.depth);
    EXPECT_FALSE(z.output.labelAovs());
    EXPECT_TRUE(parsed(patched(R"({"output": {"operator_id": true}})")).output.operatorId);
}

TEST(OutputChannels, RefusesUnknownRepeatedOrTooManyAovs) {
    std::string e = parseError(patched(R"({"output": {"aovs": ["Z", "depth"]}})"));
    EXPECT_TRUE(mentions(e, "/output/aovs/1")) << e;
    EXPECT_TRUE(mentions(e, "\"depth\"")) << e;
    e = parseError(patched(R"({"output": {"aovs": ["Z", "Z"]}})"));
    EXPECT_TRUE(mentions(e, "/output/aovs/1")) << e;
    EXPECT_TRUE(mentions(e, "twice")) << e;
    e = parseError(patched(R"({"output": {"aovs": "Z"}})"));
    EXPECT_TRUE(mentions(e, "/output/aovs")) << e;
    e = parseError(patched(R"({"output": {"aovs": ["z"]}})"));
    EXPECT_TRUE(mentions(e, "/output/aovs/0")) << e << " (channel names are case-sensitive)";
}

TEST(OutputChannels, LabelChannelsNeedALabelVolume) {
    std::string e = parseError(patched(R"({"output": {"aovs": ["label"]}})"));
    EXPECT_TRUE(mentions(e, "/output/aovs/0")) << e;
    EXPECT_TRUE(mentions(e, "/labels")) << e;
    e = parseError(patched(R"({"output": {"mattes": ["brain"]}})"));
    EXPECT_TRUE(mentions(e, "/output/mattes")) << e;
    EXPECT_TRUE(mentions(e, "/labels")) << e;
    EXPECT_EQ(parseError(withLabels(R"({"aovs": ["label"]})")), "") << "control: with labels";
}

TEST(OutputChannels, RefusesUnknownRepeatedOrTooManyMattes) {
    std::string e = parseError(withLabels(R"({"mattes": ["brain", "liver"]})"));
    EXPECT_TRUE(mentions(e, "/output/mattes/1")) << e;
    EXPECT_TRUE(mentions(e, "\"liver\"")) << e;
    e = parseError(withLabels(R"({"mattes": ["br*"]})"));
    EXPECT_TRUE(mentions(e, "/output/mattes/0")) << e << " (no patterns)";
    e = parseError(withLabels(R"({"mattes": ["brain", 3]})"));
    EXPECT_TRUE(mentions(e, "/output/mattes/1")) << e;
    EXPECT_TRUE(mentions(e, "already has a matte")) << e;
    e = parseError(withLabels(R"({"mattes": [0, 1, 2, 3, 4, 5, 6]})"));
    EXPECT_TRUE(mentions(e, "/output/mattes")) << e;
    EXPECT_TRUE(mentions(e, "1 to 6")) << e;
    e = parseError(withLabels(R"({"mattes": []})"));
    EXPECT_TRUE(mentions(e, "/output/mattes")) << e;
    e = parseError(withLabels(R"({"mattes": [-1]})"));
    EXPECT_TRUE(mentions(e, "/output/mattes/0")) << e;
    EXPECT_EQ(parseError(withLabels(R"({"mattes": [0, 1, 2, 3, 4, 5]})")), "")
        << "control: six mattes, ids without names";
}

TEST(OutputChannels, SequentialCompositionRefusesLabelChannels) {
    nlohmann::json document = withLabels(R"({"aovs": ["label"]})");
    document["render"] = {{"operator_composition", "sequential"}};
    const nlohmann::json op = nlohmann::json::parse(
        R"({"type": "dilator", "placement": {"translate": [0, 0, 0], "scale": [10, 10, 10]}})");
    document["operators"] = {op};
    EXPECT_EQ(parseError(document), "") << "control: one operator composes as one pass";
    document["operators"].push_back(op);
    const std::string e = parseError(document);
    EXPECT_TRUE(mentions(e, "/output/aovs")) << e;
    document["output"] = {{"aovs", {"Z"}}};
    EXPECT_EQ(parseError(document), "") << "Z needs no labels";
}

} // namespace
} // namespace cutaway::test
