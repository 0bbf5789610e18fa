// The validating JSON reader on its own: formatting, suggestions, typed getters,
// unknown keys, accumulation of errors.
#include "core/error.hpp"
#include "scene/json_reader.hpp"

#include <gtest/gtest.h>

namespace cutaway {
namespace {

using nlohmann::json;

TEST(JsonText, FormatsNumbersShortest) {
    EXPECT_EQ(formatNumber(0.05), "0.05");
    EXPECT_EQ(formatNumber(10000.0), "10000");
    EXPECT_EQ(formatNumber(-90.0), "-90");
    EXPECT_EQ(formatNumber(1.0e30), "1e+30");
    // Arithmetic's noise past 15 significant digits is not shown; a value
    // the user could have typed keeps every digit.
    EXPECT_EQ(formatNumber(1.37384 + 2.3e-16), "1.37384");
    EXPECT_EQ(formatNumber(0.1 + 0.2), "0.3");
    EXPECT_EQ(formatNumber(1.0000000000001), "1.0000000000001");
    EXPECT_EQ(formatNumber(123456.789012345), "123456.789012345");
    EXPECT_EQ(describeValue(nlohmann::json(0.1 + 0.2)), "0.3");
    EXPECT_EQ(describeValue(nlohmann::json(2.5)), "2.5");
    EXPECT_EQ(describeValue(nlohmann::json(7)), "7");
}

TEST(JsonText, DescribesRanges) {
    EXPECT_EQ(Range::closed(0, 1).describe(), " in [0, 1]");
    EXPECT_EQ(Range::open(0, 170).describe(), " in (0, 170)");
    EXPECT_EQ(Range::openClosed(0, 1e4).describe(), " in (0, 10000]");
    EXPECT_EQ(Range::atLeast(0).describe(), " >= 0");
    EXPECT_EQ(Range::any().describe(), "");
}

TEST(JsonText, RangesRespectOpenAndClosedBounds) {
    EXPECT_TRUE(Range::closed(0, 1).contains(0));
    EXPECT_TRUE(Range::closed(0, 1).contains(1));
    EXPECT_FALSE(Range::open(0, 1).contains(0));
    EXPECT_FALSE(Range::open(0, 1).contains(1));
    EXPECT_TRUE(Range::open(0, 1).contains(0.5));
    EXPECT_FALSE(Range::any().contains(std::numeric_limits<double>::infinity()));
    EXPECT_FALSE(Range::any().contains(std::numeric_limits<double>::quiet_NaN()));
}

TEST(JsonText, AbbreviatesLongValues) {
    EXPECT_EQ(describeValue(json(-5)), "-5");
    EXPECT_EQ(describeValue(json("high")), "\"high\"");
    EXPECT_EQ(describeValue(json::parse("[1, 2]")), "[1,2]");
    const std::string longText = describeValue(json(std::string(200, 'x')));
    EXPECT_EQ(longText.size(), 40u);
    EXPECT_EQ(longText.substr(37), "...");
}

TEST(JsonText, EditDistanceAndSuggestions) {
    EXPECT_EQ(editDistance("fovv", "fov"), 1u);
    EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
    EXPECT_EQ(editDistance("", "abc"), 3u);
    // A swap of neighbours is one edit (two for Levenshtein): the commonest typo.
    EXPECT_EQ(editDistance("szie", "size"), 1u);
    EXPECT_EQ(editDistance("ca", "abc"), 3u); // no substring is edited twice
    EXPECT_EQ(closestMatch("szie", {"spacing", "size", "window"}),
              std::optional<std::string>("size"));
    const std::vector<std::string> keys = {"fov", "projection", "ortho_height", "orbit"};
    EXPECT_EQ(closestMatch("fovv", keys), "fov");
    EXPECT_EQ(closestMatch("FOV", keys), "fov");
    EXPECT_EQ(closestMatch("orthoheight", keys), "ortho_height");
    EXPECT_EQ(closestMatch("zoom", keys), std::nullopt);
    EXPECT_EQ(closestMatch("x", {}), std::nullopt);
}

TEST(JsonText, EscapesPointerTokens) {
    EXPECT_EQ(escapePointerToken("a/b~c"), "a~1b~0c");
}

TEST(JsonText, SyntaxErrorsNameLineAndColumn) {
    try {
        parseJsonText("{\n \"a\": 1,\n \"b\": tru }", "x.json");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("x.json:3:10: JSON syntax error: ", 0), 0u)
            << e.what();
    }
}

TEST(JsonText, NestingIsLimitedBeforeParsing) {
    EXPECT_NO_THROW(parseJsonText(std::string(64, '[') + std::string(64, ']'), "x"));
    EXPECT_THROW(parseJsonText(std::string(65, '[') + std::string(65, ']'), "x"), InputError);
    // Brackets inside strings (escaped quotes too) do not count.
    const std::string text = "[\"\\\"" + std::string(100, '[') + "\"]";
    EXPECT_NO_THROW(parseJsonText(text, "x"));
}

TEST(JsonReader, ReadsTypedValuesWithDefaults) {
    const json value = json::parse(R"({"n": 0.5, "i": 7, "b": true, "s": "big",
        "v": [1, 2, 3], "c": [0, 0.5, 1], "list": [1, 2]})");
    Diagnostics diagnostics("t");
    JsonReader reader(value, diagnostics);
    EXPECT_EQ(reader.number("n", 0.0, 0.0, 1.0), 0.5);
    EXPECT_EQ(reader.number("absent", 3.0, 0.0, 10.0), 3.0);
    EXPECT_EQ(reader.integer("i", 0, 0, 10), 7);
    EXPECT_TRUE(reader.boolean("b", false));
    EXPECT_EQ(reader.string("s", "little", {"little", "big"}), "big");
    EXPECT_EQ(reader.vec3("v", glm::dvec3(0.0)), glm::dvec3(1, 2, 3));
    EXPECT_EQ(reader.colour("c", glm::vec3(1.0f)), glm::vec3(0, 0.5f, 1));
    EXPECT_EQ(reader.numbers("list", 1, 3).value(), (std::vector<double>{1, 2}));
    reader.finish();
    EXPECT_TRUE(diagnostics.empty());
    EXPECT_NO_THROW(diagnostics.throwIfAny());
}

TEST(JsonReader, AccumulatesErrorsWithPointers) {
    const json value = json::parse(R"({"sub": {"n": 2, "s": "lttle", "c": [0, 2, 0], "extra": 1},
        "list": [{"x": 1}, 5], "i": 1.5, "req": {}})");
    Diagnostics diagnostics("t.json");
    JsonReader reader(value, diagnostics);
    reader.object("sub", [](JsonReader& sub) {
        EXPECT_EQ(sub.number("n", 1.0, 0.0, 1.0), 1.0); // the default when invalid
        EXPECT_EQ(sub.string("s", "big", {"little", "big"}), "big");
        sub.colour("c", glm::vec3(0.0f));
    });
    reader.objects("list", 0, 4, [](JsonReader& item, std::size_t) { item.number("x", 0, 0, 1); });
    reader.integer("i", 0, 0, 10);
    reader.object("req", [](JsonReader& req) { req.number("needed", Range::closed(0, 1), true); });
    reader.finish();
    reader.finish(); // idempotent
    const std::vector<std::string> expected = {
        "t.json: /sub/n: expected a number in [0, 1], got 2",
        "t.json: /sub/s: expected one of \"little\", \"big\" (did you mean \"little\"?), got "
        "\"lttle\"",
        "t.json: /sub/c/1: expected a number in [0, 1], got 2",
        "t.json: /sub/extra: unknown key",
        "t.json: /list/1: expected an object, got 5",
        "t.json: /i: expected an integer in [0, 10], got 1.5",
        "t.json: /req/needed: missing; expected a number in [0, 1]",
    };
    EXPECT_EQ(diagnostics.messages(), expected);
    try {
        diagnostics.throwIfAny();
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).find(expected[0] + "\n" + expected[1]), 0u);
    }
}

TEST(JsonReader, ReportsNonObjectsAndWrongShapes) {
    Diagnostics diagnostics("t");
    const json root = json::array();
    JsonReader reader(root, diagnostics);
    EXPECT_EQ(reader.number("x", 4.0, 0.0, 1.0), 4.0);
    reader.finish();
    const json value = json::parse(R"({"v": [1, 2], "w": "x", "b": 1, "list": [1]})");
    JsonReader other(value, "/o", diagnostics);
    other.vec3("v");
    other.integers("w", 2, 2, 1, 9);
    other.boolean("b", false);
    other.objects("list", 2, 3, [](JsonReader&, std::size_t) {});
    other.finish();
    const std::vector<std::string> expected = {
        "t: (root): expected an object, got []",
        "t: /o/v: expected an array of 3 numbers, got [1,2]",
        "t: /o/w: expected an array of 2 integers in [1, 9], got \"x\"",
        "t: /o/b: expected true or false, got 1",
        "t: /o/list: expected an array of 2 to 3 objects, got [1]",
    };
    EXPECT_EQ(diagnostics.messages(), expected);
}

TEST(JsonReader, IntegersAcceptIntegralFloatsAndRejectHugeOnes) {
    const json value = json::parse(R"({"a": 512.0, "b": 18446744073709551615, "c": -3})");
    Diagnostics diagnostics("t");
    JsonReader reader(value, diagnostics);
    EXPECT_EQ(reader.integer("a", 0, 0, 1000), 512);
    EXPECT_EQ(reader.integer("b", 1, 0, std::numeric_limits<std::int64_t>::max()), 1);
    EXPECT_EQ(reader.integer("c", 0, std::numeric_limits<std::int64_t>::min(), 0), -3);
    ASSERT_EQ(diagnostics.messages().size(), 1u);
    EXPECT_EQ(diagnostics.messages()[0],
              "t: /b: expected an integer >= 0, got 18446744073709551615");
}

TEST(JsonReader, ReservedKeysHaveTheirOwnMessage) {
    const json value = json::parse(R"({"later": {}, "a/b": 1})");
    Diagnostics diagnostics("t");
    JsonReader reader(value, "/x", diagnostics);
    reader.reserved("later");
    reader.reserved("absent");
    reader.finish();
    const std::vector<std::string> expected = {
        "t: /x/later: not supported yet by this version of cutaway",
        "t: /x/a~1b: unknown key",
    };
    EXPECT_EQ(diagnostics.messages(), expected);
}

} // namespace
} // namespace cutaway
