// loadScene: files, syntax errors, nesting bombs, the example scenes in
// scenes/ and the bad scenes in tests/scene/bad/.
#include "scene/scene_test_util.hpp"

#include <algorithm>
#include <chrono>
#include <gtest/gtest.h>
#include <map>
#include <set>

namespace cutaway {
namespace {

namespace fs = std::filesystem;
using test::lines;
using test::loadError;

const fs::path kSourceDir = CUTAWAY_SOURCE_DIR;

TEST(SceneLoad, LoadsAFileAndResolvesAgainstItsFolder) {
    test::TempDir dir;
    dir.write("data/scan.nrrd", "x");
    const fs::path file = dir.write("scenes/a.json", R"({"version": 1,
        "volume": {"file": "../data/scan.nrrd"}, "output": {"pattern": "out/a_####.exr"}})");
    const Scene scene = loadScene(file);
    EXPECT_EQ(scene.file, file);
    EXPECT_EQ(scene.baseDir, dir.path() / "scenes");
    EXPECT_EQ(scene.volume.file, dir.path() / "data/scan.nrrd");
    EXPECT_EQ(scene.output.pattern, (dir.path() / "scenes/out/a_####.exr").string());
    EXPECT_EQ(scene.document["volume"]["file"], "../data/scan.nrrd");
}

TEST(SceneLoad, RelativeSceneFileGivesAbsoluteBaseDir) {
    test::TempDir dir;
    dir.write("s/a.json", R"({"version": 1, "volume": {"phantom": "orange"}})");
    const fs::path previous = fs::current_path();
    fs::current_path(dir.path());
    const Scene scene = loadScene("s/a.json");
    fs::current_path(previous);
    EXPECT_TRUE(scene.baseDir.is_absolute());
    EXPECT_EQ(scene.baseDir, dir.path() / "s");
    EXPECT_EQ(scene.file, fs::path("s/a.json"));
}

TEST(SceneLoad, ErrorsNameTheFile) {
    test::TempDir dir;
    const fs::path file = dir.write("a.json", R"({"version": 1, "volume": {"phantom": "x"}})");
    EXPECT_EQ(loadError(file).rfind(file.string() + ": /volume/phantom: expected one of", 0), 0u);
}

TEST(SceneLoad, SyntaxErrorsNameLineAndColumn) {
    test::TempDir dir;
    const fs::path file = dir.write("a.json", "{\n  \"version\": 1,\n  \"volume\": {,\n}\n");
    const std::string message = loadError(file);
    EXPECT_EQ(message.rfind(file.string() + ":3:14: JSON syntax error: ", 0), 0u) << message;
    EXPECT_EQ(lines(message).size(), 1u);

    const fs::path empty = dir.write("empty.json", "");
    EXPECT_EQ(loadError(empty).rfind(empty.string() + ":1:1: JSON syntax error: ", 0), 0u)
        << loadError(empty);
}

TEST(SceneLoad, NumbersTooLargeForADoubleAreLocated) {
    test::TempDir dir;
    const fs::path file = dir.write("a.json", "{\"version\": 1,\n \"x\": 1e400}");
    EXPECT_EQ(loadError(file),
              file.string() + ":2:7: expected a number that fits a double, got 1e400");
}

TEST(SceneLoad, NestingBombIsRejectedBeforeParsing) {
    test::TempDir dir;
    const std::string deep = std::string(10'000'000, '[') + std::string(10'000'000, ']');
    const fs::path file = dir.write("bomb.json", deep);
    const std::string message = loadError(file);
    EXPECT_EQ(message, file.string() +
                           ":1:65: nesting deeper than 64 levels (arrays and objects inside "
                           "each other)");
}

// A key written twice in one object is an error naming the pointer and both
// places, at any depth; the same key in two objects, or in an array's
// objects, is not (the control), nor is a key's text inside a string value.
TEST(SceneLoad, AKeyWrittenTwiceIsAnErrorNamingBothPlaces) {
    test::TempDir dir;
    const fs::path twice = dir.write("twice.json", "{\"version\": 1,\n"
                                                   " \"render\": {\"size\": [8, 8],\n"
                                                   "   \"size\": [16, 16]}}");
    EXPECT_EQ(loadError(twice), twice.string() +
                                    ":3:4: /render/size: the key \"size\" is written twice in "
                                    "one object (first at 2:13); a scene says each thing once");
    const fs::path nested =
        dir.write("nested.json", "{\"version\": 1, \"operators\": [{\"type\": \"peeler\"}, "
                                 "{\"type\": \"peeler\", \"params\": {\"a/b\": 1, \"a/b\": 2}}]}");
    const std::string message = loadError(nested);
    EXPECT_NE(message.find(": /operators/1/params/a~1b: the key \"a/b\" is written twice"),
              std::string::npos)
        << message;
    const fs::path fine =
        dir.write("fine.json", "{\"version\": 1, \"volume\": {\"phantom\": \"head\"},\n"
                               " \"render\": {\"size\": [8, 8]},\n"
                               " \"camera\": {\"fov\": 30}, \"output\": {\"pattern\": \"size\"}}");
    EXPECT_EQ(loadError(fine), "") << "control: each key once in its own object";
    EXPECT_EQ(loadError(dir.write("top.json", "{\"version\": 1, \"version\": 1}")),
              (dir.path() / "top.json").string() +
                  ":1:16: /version: the key \"version\" is written twice in one object (first "
                  "at 1:2); a scene says each thing once");
}

TEST(SceneLoad, EveryExampleSceneParses) {
    std::vector<fs::path> scenes;
    for (const auto& entry : fs::directory_iterator(kSourceDir / "scenes")) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() == ".json" && name.find(".schema.") == std::string::npos)
            scenes.push_back(entry.path());
    }
    std::sort(scenes.begin(), scenes.end());
    ASSERT_GE(scenes.size(), 3u);
    std::vector<std::string> skipped;
    for (const fs::path& file : scenes) {
        SCOPED_TRACE(file.string());
        const std::string message = loadError(file);
        if (message.empty()) continue;
        // A scene that reads a real scan (and its labels) from ../shared/data,
        // or a DICOM series scripts/write_dicom.py writes into out/dicom/:
        // when they are absent the only problems may be those files.
        const auto found = lines(message);
        ASSERT_GE(found.size(), 1u) << message;
        ASSERT_LE(found.size(), 2u) << message;
        EXPECT_NE(found[0].find(": /volume/file: no such file: "), std::string::npos) << message;
        if (found.size() == 2) {
            EXPECT_NE(found[1].find(": /labels/file: no such file: "), std::string::npos)
                << message;
        }
        for (const std::string& line : found)
            EXPECT_TRUE(line.find("shared/data/") != std::string::npos ||
                        line.find("out/dicom/") != std::string::npos)
                << message;
        skipped.push_back(file.filename().string());
    }
    if (!skipped.empty()) {
        std::string names;
        for (const auto& name : skipped)
            names += " " + name;
        GTEST_SKIP() << "scenes whose scan is absent (../shared/data, or a DICOM series not "
                        "yet written):"
                     << names;
    }
}

// The default demo needs no scan and shows what cutaway is for: an operator.
TEST(SceneLoad, DemoSceneIsTheHeadPhantomWithAnOperator) {
    const Scene scene = loadScene(kSourceDir / "scenes/demo.json");
    EXPECT_EQ(scene.volume.phantom, "head");
    EXPECT_EQ(scene.operators.size(), 1u);
    EXPECT_EQ(scene.volume.phantomSize, glm::ivec3(160));
    EXPECT_EQ(scene.render.width, 512);
    EXPECT_TRUE(scene.output.png);
    EXPECT_EQ(scene.output.pattern, (kSourceDir / "out/demo_####.exr").lexically_normal().string());
}

// Each file in tests/scene/bad/ has exactly one mistake; the message must be
// one line containing the expected text (usually the JSON pointer).
const std::map<std::string, std::string> kBadScenes = {
    {"01-missing-version.json", ": /version: missing; add \"version\": 1"},
    {"02-unsupported-version.json", ": /version: unsupported version: expected 1, got 2"},
    {"03-unknown-section.json", ": /rendr: unknown key (did you mean \"render\"?)"},
    {"04-fov-wrong-type.json", ": /camera/fov: expected a number in (0, 170), got \"wide\""},
    {"05-size-negative.json", ": /render/size/0: expected an integer in [1, 16384], got -5"},
    {"06-no-volume-source.json", ": /volume: expected exactly one of \"file\" or \"phantom\""},
    {"07-unknown-phantom.json", ": /volume/phantom: expected one of \"head\", \"orange\""},
    {"08-missing-volume-file.json", ": /volume/file: no such file: "},
    {"09-transfer-not-increasing.json",
     ": /transfer/points/2/value: expected a value greater than the previous point's (90)"},
    {"10-transfer-one-point.json", ": /transfer/points: expected an array of at least 2"},
    {"11-colour-out-of-range.json", ": /transfer/points/1/color/0: expected a number in [0, 1]"},
    {"12-orbit-and-look-at.json", ": /camera: expected at most one of \"orbit\" or \"look_at\""},
    {"13-up-parallel-to-view.json", ": /camera/look_at/up: expected a direction not parallel"},
    {"14-too-many-lights.json", ": /lights/directional: expected an array of at most 4"},
    {"15-background-string.json", ": /render/background: expected an array of 3 or 4 numbers"},
    {"16-operator-unknown-type.json",
     ": /operators/0/type: expected one of \"peeler\", \"retractor\", \"pliers\", \"dilator\", "
     "got \"peel\""},
    {"17-syntax-error.json", "17-syntax-error.json:4:10: JSON syntax error: "},
    {"18-elevation-90.json", ": /camera/orbit/elevation: expected a number in (-90, 90)"},
    {"19-pixel-type.json", ": /output/pixel_type: expected one of \"half\", \"float\""},
    {"20-empty-pattern.json", ": /output/pattern: expected a non-empty string, got \"\""},
    {"21-nesting-bomb.json", ": nesting deeper than 64 levels"},
    {"22-unknown-key-typo.json", ": /camera/fovv: unknown key (did you mean \"fov\"?)"},
    {"23-raw-with-phantom.json", ": /volume/raw: only allowed with \"file\""},
    {"24-shading-enabled-string.json", ": /render/shading/enabled: expected true or false"},
    {"25-huge-intensity.json",
     ": /lights/directional/0/intensity: expected a number in [0, 10], got 1e+300"},
    {"26-root-is-array.json", ": (root): expected an object (a scene), got [1,2,3]"},
    {"27-number-overflow.json", ":4:32: expected a number that fits a double, got 1e400"},
    {"28-frames-reversed.json", ": /animation/frames: expected the first frame <= the last"},
    {"29-track-target-not-pointer.json",
     ": /animation/tracks/0/target: expected a JSON pointer such as"},
    {"30-keys-not-increasing.json",
     ": /animation/tracks/0/keys/1/frame: expected a frame greater than the previous key's (10)"},
    {"31-key-shape-mismatch.json",
     ": /animation/tracks/0/keys/1/value: expected the same shape as key 0's value"},
    {"32-interpolation-unknown.json", ": /animation/tracks/0/interpolation: expected one of"},
    {"33-classification-unknown.json",
     ": /render/classification: expected one of \"preintegrated\", \"post\""},
    {"34-fps-zero.json", ": /animation/fps: expected a number in (0, 1000], got 0"},
    {"35-key-without-value.json", ": /animation/tracks/0/keys/0/value: missing"},
    {"36-pliers-do-not-converge.json",
     ": /operators/0/params/displacement: expected |displacement| * 1.72 / radius < 0.95"},
    {"37-operator-angle-string.json",
     ": /operators/1/params/angle: expected a number in [0, 180], got \"90deg\""},
    {"38-label-name-unknown.json",
     ": /operators/0/alignment/labels/0: unknown label name \"skul\" (did you mean \"skull\"?)"},
    {"39-segment-without-labels-section.json",
     ": /operators/0/alignment/labels: labels need a /labels section (a label volume)"},
    {"40-segment-labels-and-range.json",
     ": /operators/0/alignment: segment alignment needs exactly one of \"labels\" or \"range\", "
     "got both"},
    {"41-threshold-not-otsu.json",
     ": /operators/0/alignment/threshold: expected a number or \"otsu\", got \"auto\""},
    {"42-alignment-depth-zero.json",
     ": /operators/0/alignment/depth: expected a number in (0, 10000], got 0"},
    {"43-phantom-labels-with-file-volume.json",
     ": /labels/phantom: the volume is not a phantom: give the label \"file\""},
    {"44-depth-with-segment-mode.json",
     ": /operators/0/alignment/depth: only with \"mode\": \"surface\""},
    {"45-transfer-labels-without-labels.json",
     ": /transfer/labels/0/labels: labels need a /labels section (a label volume)"},
    {"46-segment-range-reversed.json",
     ": /operators/0/alignment/range: expected [lo, hi] with lo <= hi, got [250,200]"},
    {"47-sequential-segment-by-labels.json",
     ": /operators/1/alignment/labels: under \"operator_composition\": \"sequential\" the scan "
     "is resampled and its labels no longer match: use \"range\""},
    {"48-label-file-missing.json", ": /labels/file: no such file: "},
    {"49-label-id-negative.json",
     ": /labels/names/tumour: expected an integer in [0, 2147483647], got -4"},
    {"50-transfer-label-without-points.json",
     ": /transfer/labels/0/points: missing; expected an array of at least 2 objects"},
    {"51-truncated.json",
     ":4:38: JSON syntax error: while parsing object - unexpected end of input"},
    {"52-size-zero.json", ": /volume/size/1: expected an integer in [8, 1024], got 0"},
    {"53-nan-literal.json", ":4:22: JSON syntax error: while parsing value - invalid literal"},
    {"54-filter-unknown.json", ": /render/filter: expected one of \"linear\", \"cubic\""},
    {"55-cut-face-on-pliers.json",
     ": /operators/0/cut_face: pliers cut nothing: only \"peeler\" and \"retractor\" take it"},
    {"56-refine-out-of-range.json", ": /render/refine: expected an integer in [1, 8], got 16"},
    {"57-unit-distance-negative.json",
     ": /transfer/unit_distance: expected a number in (0, 1000000], got -1"},
    {"58-cut-antialias-out-of-range.json",
     ": /render/cut_antialias: expected a number in [0, 4], got 5"},
    {"60-label-pattern-matches-none.json",
     ": /operators/0/alignment/labels/0: no label name matches the pattern \"brian*\" (did you "
     "mean \"brain\"?)"},
    {"61-label-table-and-names.json",
     ": /labels: expected at most one of \"table\" or \"names\", got both"},
    {"62-color-table-without-table.json",
     ": /transfer/labels/0/color: \"table\" needs a /labels/table"},
    {"63-label-table-bad-line.json", "tables/bad_line.txt:3: not a label line"},
    {"64-camera-margin-too-wide.json", "/camera/margin: expected a number in [0, 0.45]"},
    {"65-camera-zoom-with-look-at.json", "/camera/zoom: acts on a fitted view"},
    {"66-output-aov-unknown.json", "/output/aovs/1: expected"},
    {"67-key-written-twice.json", ":2:33: /render/size: the key \"size\" is written twice"},
    {"59-series-without-dicom.json",
     ": /volume/series: only allowed with a DICOM file, folder or DICOMDIR as \"file\""},
};

TEST(SceneLoad, BadScenesGiveTheirOneError) {
    const fs::path folder = kSourceDir / "tests/scene/bad";
    std::set<std::string> files;
    for (const auto& entry : fs::directory_iterator(folder)) {
        files.insert(entry.path().filename().string());
    }
    EXPECT_GE(files.size(), 30u);
    for (const auto& [name, expected] : kBadScenes) {
        EXPECT_TRUE(files.count(name)) << "missing bad scene " << name;
    }
    for (const std::string& name : files) {
        SCOPED_TRACE(name);
        const auto it = kBadScenes.find(name);
        ASSERT_NE(it, kBadScenes.end()) << "add " << name << " to kBadScenes";
        const fs::path file = folder / name;
        const std::string message = loadError(file);
        ASSERT_FALSE(message.empty()) << "loaded without error";
        EXPECT_EQ(message.rfind(file.string(), 0), 0u) << message; // names the file first
        EXPECT_NE(message.find(it->second), std::string::npos) << message;
        EXPECT_EQ(lines(message).size(), 1u) << message;
    }
}

} // namespace
} // namespace cutaway
