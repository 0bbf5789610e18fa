// What a scene's text may be: files that are not regular files, oversized
// files and strings, values nested too deep (in the file or on the command
// line), and how much of a value a message quotes.
#include "io/json_limits.hpp"
#include "io/named_pipe.hpp"
#include "scene/animation.hpp"
#include "scene/json_reader.hpp"
#include "scene/scene_test_util.hpp"

#include <gtest/gtest.h>
#include <string>

namespace cutaway {
namespace {

namespace fs = std::filesystem;
using test::loadError;

// Arrays `depth` deep, built without the recursive parser.
nlohmann::json nested(int depth) {
    nlohmann::json value = nlohmann::json::array();
    for (int i = 1; i < depth; ++i)
        value = nlohmann::json::array({std::move(value)});
    return value;
}

std::string setError(const std::string& assignment) {
    try {
        parseSetting(assignment);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(SceneInput, OnlyARegularFileIsReadAsAScene) {
    test::TempDir dir;
    EXPECT_EQ(loadError(dir.path() / "none.json"),
              (dir.path() / "none.json").string() + ": cannot read scene (no such file)");
    EXPECT_EQ(loadError(dir.path()),
              dir.path().string() + ": cannot read scene (it is a folder, not a regular file)");
    // A pipe nobody writes to is refused without being opened: open() would block.
    const test::NamedPipe pipe(dir.path() / "pipe.json");
    ASSERT_TRUE(pipe.made());
    EXPECT_EQ(loadError(pipe.path()), pipe.path().string() +
                                          ": cannot read scene (it is a named pipe (FIFO), not a "
                                          "regular file)");
    EXPECT_FALSE(pipe.wasOpened());
    // Endless: read until memory ran out.
    if (fs::exists("/dev/zero")) {
        EXPECT_EQ(loadError("/dev/zero"),
                  "/dev/zero: cannot read scene (it is a character device, not a regular file)");
    }
    // The control: a regular file with the same text is read.
    const fs::path file = dir.write("ok.json", R"({"version": 1, "volume": {"phantom": "head"}})");
    EXPECT_EQ(loadError(file), "");
}

TEST(SceneInput, AFileLargerThanAnySceneIsRefusedUnread) {
    test::TempDir dir;
    const fs::path big = dir.write("big.json", "");
    fs::resize_file(big, kMaxSceneBytes + 1); // sparse: nothing to write
    EXPECT_EQ(loadError(big), big.string() + ": cannot read scene (it is larger than the 64 MiB "
                                             "a scene may be)");
    fs::resize_file(big, kMaxSceneBytes); // at the limit it is read: zeros are no JSON
    EXPECT_NE(loadError(big).find("JSON syntax error"), std::string::npos) << loadError(big);
}

TEST(SceneInput, AStringLongerThanAMebibyteIsRefusedWhereItStarts) {
    const std::string longKey(kMaxSceneStringBytes + 1, 'k');
    const std::string text = "{\"version\": 1,\n \"" + longKey + "\": 1}";
    try {
        parseJsonText(text, "big.json");
        FAIL() << "parsed";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "big.json:2:2: a string longer than 1024 KiB, more than any value here may hold");
    }
    // At the limit: parsed.
    const std::string atLimit = "{\"" + std::string(kMaxSceneStringBytes, 'k') + "\": 1}";
    EXPECT_NO_THROW(parseJsonText(atLimit, "big.json"));
}

TEST(SceneInput, MessagesQuoteAboutFortyCharactersOfAnyValue) {
    // An unknown key of 512 KiB: one short line (no typo hint is looked
    // for: that took time and memory in proportion to the key's length).
    nlohmann::json document = test::minimalScene();
    document[std::string(512 << 10, 'k')] = 1;
    const std::string message = test::parseError(document);
    EXPECT_EQ(message, "scene.json: /" + std::string(36, 'k') + "...: unknown key")
        << message.substr(0, 200);

    // A string value of a megabyte, 60,000 arrays inside each other.
    document = test::minimalScene();
    document["render"]["size"] = std::string(1 << 20, 'x');
    EXPECT_EQ(test::parseError(document),
              "scene.json: /render/size: expected an array of 2 integers in [1, 16384], got \"" +
                  std::string(36, 'x') + "...");
    document["render"]["size"] = nested(60000);
    EXPECT_EQ(test::parseError(document),
              "scene.json: /render/size: expected an array of 2 integers in [1, 16384], got " +
                  std::string(37, '[') + "...");
    // Short values are quoted whole (the control).
    document["render"]["size"] = nlohmann::json::array({1, 2, 3});
    EXPECT_EQ(test::parseError(document),
              "scene.json: /render/size: expected an array of 2 integers in [1, 16384], got "
              "[1,2,3]");
    EXPECT_EQ(describeValue(nlohmann::json{{"a", {1.5, "x"}}}), "{\"a\":[1.5,\"x\"]}");
}

TEST(SceneInput, SetValuesMeetTheLimitsOfSceneFiles) {
    const std::string deep = std::string(60000, '[') + std::string(60000, ']');
    EXPECT_EQ(setError("/render/size=" + deep),
              "--set /render/size:1:65: nesting deeper than 64 levels (arrays and objects inside "
              "each other)");
    const std::string atLimit = std::string(64, '[') + std::string(64, ']');
    EXPECT_EQ(setError("/render/size=" + atLimit), "");
    EXPECT_NE(setError("/output/pattern=\"" + std::string(kMaxSceneStringBytes + 1, 'x') + "\"")
                  .find("--set /output/pattern: a value of 1024 KiB"),
              std::string::npos);
    // A malformed assignment is quoted in part.
    const std::string message = setError(std::string(100000, 'x'));
    EXPECT_EQ(message, "--set " + std::string(37, 'x') +
                           "...: expected /json/pointer=VALUE, e.g. /camera/orbit/azimuth=90");
}

TEST(SceneInput, VersionOnePointZeroIsOne) {
    nlohmann::json document = test::minimalScene();
    document["version"] = 1.0;
    EXPECT_EQ(test::parseError(document), "");
    document["version"] = 1.5;
    EXPECT_EQ(test::parseError(document),
              "scene.json: /version: unsupported version: expected 1, got 1.5");
    document["version"] = 2;
    EXPECT_EQ(test::parseError(document),
              "scene.json: /version: unsupported version: expected 1, got 2");
    document["version"] = "1";
    EXPECT_EQ(test::parseError(document),
              "scene.json: /version: unsupported version: expected 1, got \"1\"");
}

TEST(SceneInput, InputPathsWithNulOrPastPathMaxAreRefused) {
    nlohmann::json document = nlohmann::json::parse(R"({"version": 1, "volume": {}})");
    document["volume"]["file"] = std::string("scan\0.nrrd", 10);
    EXPECT_EQ(test::parseError(document),
              "scene.json: /volume/file: expected a path without NUL characters, of fewer than "
              "4096 bytes, got \"scan\\u0000.nrrd\"");
    document["volume"]["file"] = std::string(5000, 'x');
    EXPECT_NE(test::parseError(document).find("of fewer than 4096 bytes, got \"xxxx"),
              std::string::npos);
}

} // namespace
} // namespace cutaway
