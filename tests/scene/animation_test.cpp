// Animation tracks: parsing, interpolation at and between keys for each mode,
// and per-frame validation of the evaluated scene.
#include "scene/animation.hpp"
#include "scene_test_util.hpp"

#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

Track track(Interpolation mode, std::vector<std::pair<double, double>> keys) {
    Track t;
    t.target = "/camera/orbit/azimuth";
    t.interpolation = mode;
    for (auto [f, v] : keys)
        t.keys.push_back({f, {v}, false});
    return t;
}

double at(const Track& t, double frame) {
    return evaluateTrack(t, frame).at(0);
}

} // namespace

TEST(Animation, LinearHitsKeysAndInterpolatesBetween) {
    Track t = track(Interpolation::Linear, {{0, 10}, {10, 30}, {30, -10}});
    EXPECT_DOUBLE_EQ(at(t, 0), 10);
    EXPECT_DOUBLE_EQ(at(t, 10), 30);
    EXPECT_DOUBLE_EQ(at(t, 30), -10);
    EXPECT_DOUBLE_EQ(at(t, 5), 20);
    EXPECT_DOUBLE_EQ(at(t, 20), 10);
    EXPECT_DOUBLE_EQ(at(t, -5), 10);   // before the first key: held
    EXPECT_DOUBLE_EQ(at(t, 100), -10); // after the last key: held
}

TEST(Animation, StepHoldsEachKeyUntilTheNext) {
    Track t = track(Interpolation::Step, {{0, 1}, {4, 2}, {8, 3}});
    EXPECT_DOUBLE_EQ(at(t, 0), 1);
    EXPECT_DOUBLE_EQ(at(t, 3.999), 1);
    EXPECT_DOUBLE_EQ(at(t, 4), 2);
    EXPECT_DOUBLE_EQ(at(t, 7), 2);
    EXPECT_DOUBLE_EQ(at(t, 8), 3);
}

TEST(Animation, SmoothPassesThroughKeysWithContinuousSlope) {
    Track t = track(Interpolation::Smooth, {{0, 0}, {10, 10}, {15, 0}, {30, 5}});
    for (const auto& k : t.keys)
        EXPECT_NEAR(at(t, k.frame), k.value[0], 1e-12);
    // Catmull-Rom tangent at frame 10: (0 - 0) / (15 - 0) = 0, so a local maximum.
    const double h = 1e-4;
    EXPECT_NEAR((at(t, 10 + h) - at(t, 10 - h)) / (2 * h), 0.0, 1e-3);
    // Slope continuous across key 15: left and right one-sided derivatives agree.
    const double left = (at(t, 15) - at(t, 15 - h)) / h, right = (at(t, 15 + h) - at(t, 15)) / h;
    EXPECT_NEAR(left, right, 1e-3);
    // Collinear keys: smooth equals linear.
    Track line = track(Interpolation::Smooth, {{0, 0}, {10, 20}, {20, 40}});
    EXPECT_NEAR(at(line, 5), 10.0, 1e-12);
    EXPECT_NEAR(at(line, 13), 26.0, 1e-12);
    // Between keys 0 and 10 of the first track: values from the Hermite basis.
    // m0 = (10 - 0) / 10 = 1 per frame, m1 = 0; at t = 0.5: 0.5*0 + 0.125*10*1 + 0.5*10 - 0.125*0
    // = 6.25
    EXPECT_NEAR(at(t, 5), 6.25, 1e-12);
}

TEST(Animation, VectorsInterpolateComponentwise) {
    Track t;
    t.target = "/camera/orbit/target";
    t.keys = {{0, {0, 0, 0}, true}, {10, {10, -20, 5}, true}};
    EXPECT_EQ(evaluateTrack(t, 5), (std::vector<double>{5, -10, 2.5}));
}

TEST(Animation, TracksParseAndDriveTheSceneOfEachFrame) {
    nlohmann::json doc = patched(R"({"animation": {"frames": [0, 36], "fps": 12, "tracks": [
        {"target": "/camera/orbit/azimuth", "keys": [{"frame": 0, "value": 0},
                                                     {"frame": 36, "value": 360}]},
        {"target": "/lights/ambient", "interpolation": "step",
         "keys": [{"frame": 0, "value": 0.1}, {"frame": 18, "value": 0.5}]}]}})");
    Scene scene = parseScene(doc, "/nonexistent/scenes", "scene.json");
    EXPECT_EQ(scene.animation.firstFrame, 0);
    EXPECT_EQ(scene.animation.lastFrame, 36);
    EXPECT_DOUBLE_EQ(scene.animation.fps, 12);
    ASSERT_EQ(scene.animation.tracks.size(), 2u);
    Scene f9 = sceneAtFrame(scene, 9);
    EXPECT_DOUBLE_EQ(f9.camera.azimuthDeg, 90.0);
    EXPECT_FLOAT_EQ(f9.lights.ambient, 0.1f);
    EXPECT_EQ(f9.document["camera"]["orbit"]["azimuth"], 90.0); // the evaluated document
    Scene f20 = sceneAtFrame(scene, 20);
    EXPECT_FLOAT_EQ(f20.lights.ambient, 0.5f);
}

TEST(Animation, AFrameDrivenOutOfRangeIsReportedWithItsFrame) {
    nlohmann::json doc = patched(R"({"animation": {"frames": [0, 10], "tracks": [
        {"target": "/camera/fov", "keys": [{"frame": 0, "value": 30}, {"frame": 10, "value": 230}]}]}})");
    Scene scene = parseScene(doc, "/nonexistent/scenes", "scene.json");
    EXPECT_NO_THROW(sceneAtFrame(scene, 5)); // 130 degrees
    try {
        sceneAtFrame(scene, 9); // 210 degrees
        FAIL() << "expected an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("(frame 9): /camera/fov: expected a number"),
                  std::string::npos)
            << e.what();
    }
}

TEST(Animation, AValueATrackDroveOutOfRangeNamesTheTrack) {
    nlohmann::json doc = patched(R"({"render": {"size": [64, 64]}, "animation": {"frames": [0, 3],
        "tracks": [{"target": "/camera/fov", "keys": [{"frame": 0, "value": 30}, {"frame": 3, "value": 330}]},
                   {"target": "/render/size", "keys": [{"frame": 0, "value": [64, 64]}, {"frame": 3, "value": [65, 66]}]},
                   {"target": "/render/size_typo", "interpolation": "step", "keys": [{"frame": 0, "value": 1}]}]}})");
    Scene scene = parseScene(doc, "/nonexistent/scenes", "scene.json");
    const std::string error = [&] {
        try {
            sceneAtFrame(scene, 2);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    }();
    EXPECT_NE(error.find("/camera/fov: expected a number in (0, 170), got 230 (written by "
                         "/animation/tracks/0)\n"),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("/render/size/0: expected an integer in [1, 16384], got 64.6666666666667 "
                         "(written by /animation/tracks/1); a whole number between keys needs "
                         "\"interpolation\": \"step\""),
              std::string::npos)
        << error;
    // /render/size_typo lies beside /render/size, not within it.
    EXPECT_NE(error.find("/render/size_typo: unknown key (written by /animation/tracks/2)"),
              std::string::npos)
        << error;
}

TEST(Animation, BadTracksAreReportedAtTheirPointers) {
    EXPECT_NE(parseError(patched(R"({"animation": {"frames": [5, 2]}})")).find("/animation/frames"),
              std::string::npos);
    EXPECT_NE(
        parseError(
            patched(
                R"({"animation": {"tracks": [{"target": "camera", "keys": [{"frame": 0, "value": 1}]}]}})"))
            .find("/animation/tracks/0/target: expected a JSON pointer"),
        std::string::npos);
    EXPECT_NE(
        parseError(
            patched(
                R"({"animation": {"tracks": [{"target": "/animation/fps", "keys": [{"frame": 0, "value": 1}]}]}})"))
            .find("/animation/tracks/0/target"),
        std::string::npos);
    EXPECT_NE(
        parseError(
            patched(
                R"({"animation": {"tracks": [{"target": "/lights/ambient", "keys": [{"frame": 3, "value": 1}, {"frame": 3, "value": 0}]}]}})"))
            .find("/animation/tracks/0/keys/1/frame: expected a frame greater"),
        std::string::npos);
    EXPECT_NE(
        parseError(
            patched(
                R"({"animation": {"tracks": [{"target": "/camera/orbit/target", "keys": [{"frame": 0, "value": [1, 2, 3]}, {"frame": 1, "value": 4}]}]}})"))
            .find("/animation/tracks/0/keys/1/value: expected the same shape"),
        std::string::npos);
    EXPECT_NE(
        parseError(
            patched(
                R"({"animation": {"tracks": [{"target": "/lights/ambient", "interpolation": "cubic", "keys": [{"frame": 0, "value": 1}]}]}})"))
            .find("/animation/tracks/0/interpolation"),
        std::string::npos);
    EXPECT_NE(
        parseError(
            patched(R"({"animation": {"tracks": [{"target": "/lights/ambient", "keys": []}]}})"))
            .find("/animation/tracks/0/keys"),
        std::string::npos);
}

TEST(Animation, ATargetThatCannotBeWrittenNamesTheTrack) {
    nlohmann::json doc = patched(R"({"transfer": {"points": [
        {"value": 0, "color": [0,0,0], "alpha": 0}, {"value": 1, "color": [1,1,1], "alpha": 1}]},
        "animation": {"tracks": [{"target": "/transfer/points/7/alpha",
                                  "keys": [{"frame": 0, "value": 0.5}]}]}})");
    Scene scene = parseScene(doc, "/nonexistent/scenes", "scene.json");
    try {
        sceneAtFrame(scene, 0);
        FAIL() << "expected an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/animation/tracks/0/target: cannot write"),
                  std::string::npos)
            << e.what();
    }
}

// Found by fuzz_scene (fuzz/regressions/scene/track-target-*.json): nlohmann
// throws its own exceptions on these pointers, or pads a new array with nulls.
TEST(Animation, IndicesNlohmannWouldMisreadAreRefused) {
    const nlohmann::json doc = patched(R"({"render": {"size": [4, 4]}})");
    const auto problem = [&](const std::string& pointer) {
        return pointerWriteProblem(doc, pointer);
    };
    EXPECT_EQ(problem("/render/size/1"), "");
    EXPECT_EQ(problem("/camera/orbit/azimuth"), ""); // objects are created
    EXPECT_EQ(problem("/render/size/01"), "\"01\" is not an index of an array of 2");
    EXPECT_EQ(problem("/render/size/99999999999999999999999"),
              "\"99999999999999999999999\" is not an index of an array of 2");
    EXPECT_EQ(problem("/lights/100000000"),
              "\"/lights\" does not exist; only objects are created on the way");
    EXPECT_EQ(problem("/lights/directional/0/intensity"),
              "\"/lights/directional\" does not exist; only objects are created on the way");
    EXPECT_EQ(problem("/camera/orbit/"),
              "\"/camera/orbit\" does not exist; only objects are created on the way");
    EXPECT_EQ(problem("/render/"), ""); // an existing object may get the key ""
    EXPECT_EQ(problem("/camera/orbit/-"),
              "\"/camera/orbit\" does not exist; only objects are created on the way");

    for (const char* target :
         {"/lights/66666666666666666666666", "/render/size/01", "/a/7", "/a/b/"}) {
        SCOPED_TRACE(target);
        nlohmann::json scene = doc;
        scene["animation"] = nlohmann::json::parse(
            R"({"tracks": [{"target": "", "keys": [{"frame": 0, "value": 1}]}]})");
        scene["animation"]["tracks"][0]["target"] = target;
        const Scene parsed = parseScene(scene, "/nonexistent/scenes", "scene.json");
        EXPECT_THROW(sceneAtFrame(parsed, 0), InputError);
        EXPECT_THROW(applySettings(scene, {{target, 1}}), InputError);
    }
}

// A setting wins over the tracks that would write the same value, whether
// their target is the setting's pointer, inside it or holds it; others stay.
TEST(Animation, ASettingRemovesTheTracksOfItsValue) {
    const auto tracks = [](const nlohmann::json& document) {
        std::vector<std::string> targets;
        for (const auto& t : document["animation"]["tracks"])
            targets.push_back(t["target"]);
        return targets;
    };
    const nlohmann::json doc = nlohmann::json::parse(R"({ "animation": { "tracks": [
        { "target": "/camera/orbit/azimuth", "keys": [ { "frame": 0, "value": 1 } ] },
        { "target": "/camera/orbit/target", "keys": [ { "frame": 0, "value": [0, 0, 0] } ] },
        { "target": "/camera/fov", "keys": [ { "frame": 0, "value": 30 } ] },
        { "target": "/camera/orbit/azimuthal", "keys": [ { "frame": 0, "value": 1 } ] } ] } })");
    nlohmann::json a = doc;
    applySettings(a, {{"/camera/orbit/azimuth", 90}});
    EXPECT_EQ(a["camera"]["orbit"]["azimuth"], 90);
    EXPECT_EQ(tracks(a), (std::vector<std::string>{"/camera/orbit/target", "/camera/fov",
                                                   "/camera/orbit/azimuthal"}));
    nlohmann::json b = doc;
    applySettings(b, {{"/camera/orbit", nlohmann::json::object()}});
    EXPECT_EQ(tracks(b), (std::vector<std::string>{"/camera/fov"}));
    nlohmann::json c = doc;
    c["camera"]["orbit"]["target"] = {0, 0, 0};
    applySettings(c, {{"/camera/orbit/target/1", 5}});
    EXPECT_EQ(tracks(c), (std::vector<std::string>{"/camera/orbit/azimuth", "/camera/fov",
                                                   "/camera/orbit/azimuthal"}));
    nlohmann::json d = doc; // a setting of the tracks themselves removes none
    applySettings(d, {{"/animation/tracks/0/target", "/camera/fov"}});
    EXPECT_EQ(tracks(d).size(), 4u);
}

// Two tracks of one value (the same target, or one inside the other's) are
// refused: the later would silently win.
TEST(Animation, TwoTracksOfOneValueAreRefused) {
    const auto scene = [](const std::string& a, const std::string& b) {
        return nlohmann::json::parse(R"({ "version": 1, "volume": { "phantom": "head" },
          "animation": { "tracks": [
            { "target": ")" + a + R"(", "keys": [ { "frame": 0, "value": 1 } ] },
            { "target": "/camera/fov", "keys": [ { "frame": 0, "value": 30 } ] },
            { "target": ")" + b + R"(", "keys": [ { "frame": 0, "value": 2 } ] } ] } })");
    };
    const auto error = [&](const std::string& a, const std::string& b) -> std::string {
        try {
            (void)parseScene(scene(a, b), "/nonexistent", "s.json");
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(error("/camera/orbit/azimuth", "/camera/orbit/azimuth"),
              "s.json: /animation/tracks/2/target: \"/camera/orbit/azimuth\" writes what track 0 "
              "(\"/camera/orbit/azimuth\") writes; give each value one track");
    EXPECT_NE(error("/operators/0/placement/translate", "/operators/0/placement/translate/1")
                  .find("writes what track 0"),
              std::string::npos);
    EXPECT_NE(error("/camera/orbit/azimuth", "/camera/orbit").find("writes what track 0"),
              std::string::npos);
    EXPECT_EQ(error("/camera/orbit/azimuth", "/camera/orbit/elevation"), "");
    EXPECT_EQ(error("/camera/orbit/azimuth", "/camera/orbit/azimuthal"), "");
}

} // namespace cutaway::test
