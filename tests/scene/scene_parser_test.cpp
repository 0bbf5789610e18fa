// parseScene from in-memory documents: defaults, where each key goes, and the
// messages of invalid documents.
#include "scene/scene_test_util.hpp"

#include <gtest/gtest.h>

namespace cutaway {
namespace {

using nlohmann::json;
using test::lines;
using test::minimalScene;
using test::parseError;
using test::patched;

const char* const kFullExample = R"({
  "version": 1,
  "volume": { "phantom": "head", "size": [128, 96, 64], "spacing": [0.5, 0.5, 2],
              "window": [10, 240] },
  "transfer": { "points": [
      { "value": 0,   "color": [0, 0, 0],       "alpha": 0 },
      { "value": 60,  "color": [0.9, 0.6, 0.5], "alpha": 0.0 },
      { "value": 90,  "color": [0.9, 0.6, 0.5], "alpha": 0.05 },
      { "value": 200, "color": [1, 1, 0.9],     "alpha": 0.8 } ] },
  "camera": { "projection": "orthographic", "fov": 45, "ortho_height": 300,
              "orbit": { "azimuth": 30, "elevation": 15, "distance": 700, "target": [1, 2, 3],
                         "up": [0, 1, 0] } },
  "lights": { "ambient": 0.1, "headlight": 2,
              "directional": [ { "direction": [-1, 1, -1], "color": [1, 0.5, 0.25],
                                 "intensity": 0.4 },
                               { "direction": [0, 0, 1] } ] },
  "render": { "size": [640, 480], "slice_spacing": 0.5, "background": [0.1, 0.2, 0.3],
              "termination_opacity": 0.98,
              "shading": { "enabled": false, "diffuse": 0.7, "specular": 0.2, "shininess": 64 } },
  "output": { "pattern": "out/head_####.exr", "pixel_type": "float", "compression": "piz",
              "png": true }
})";

TEST(SceneParser, FillsDefaults) {
    const Scene scene = parseScene(minimalScene(), "/scenes");
    const Scene defaults;
    EXPECT_EQ(scene.version, 1);
    EXPECT_EQ(scene.baseDir, std::filesystem::path("/scenes"));
    EXPECT_TRUE(scene.file.empty());
    EXPECT_EQ(scene.document, minimalScene());
    EXPECT_EQ(scene.volume.phantom, "head");
    EXPECT_TRUE(scene.volume.file.empty());
    EXPECT_EQ(scene.volume.phantomSize, glm::ivec3(128));
    EXPECT_FALSE(scene.volume.raw.has_value());
    EXPECT_FALSE(scene.volume.spacing.has_value());
    EXPECT_FALSE(scene.volume.window.has_value());
    // The default transfer function: a grey ramp over 8-bit values.
    ASSERT_EQ(scene.transfer.points.size(), 2u);
    EXPECT_EQ(scene.transfer.points[0].value, 0.0);
    EXPECT_EQ(scene.transfer.points[0].alpha, 0.0f);
    EXPECT_EQ(scene.transfer.points[1].value, 255.0);
    EXPECT_EQ(scene.transfer.points[1].alpha, 0.6f);
    EXPECT_EQ(scene.transfer.points[1].color, glm::vec3(0.9f));
    EXPECT_EQ(scene.camera.projection, Projection::Perspective);
    EXPECT_EQ(scene.camera.fovDeg, 30.0);
    EXPECT_EQ(scene.camera.orthoHeight, 0.0);
    EXPECT_TRUE(scene.camera.useOrbit);
    EXPECT_EQ(scene.camera.azimuthDeg, 0.0);
    EXPECT_EQ(scene.camera.elevationDeg, 0.0);
    EXPECT_EQ(scene.camera.distance, 0.0);
    EXPECT_EQ(scene.camera.target, glm::dvec3(0.0));
    EXPECT_EQ(scene.camera.up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(scene.lights.ambient, defaults.lights.ambient);
    EXPECT_EQ(scene.lights.headlight, defaults.lights.headlight);
    EXPECT_TRUE(scene.lights.directional.empty());
    EXPECT_EQ(scene.render.width, 512);
    EXPECT_EQ(scene.render.height, 512);
    EXPECT_EQ(scene.render.sliceSpacing, 1.0);
    EXPECT_EQ(scene.render.terminationOpacity, 1.0 - 1.0 / 255.0);
    EXPECT_EQ(scene.render.refine, 4);
    EXPECT_EQ(scene.render.background, glm::vec4(0, 0, 0, 1));
    EXPECT_TRUE(scene.render.shading.enabled);
    EXPECT_EQ(scene.render.shading.diffuse, 0.8f);
    EXPECT_EQ(scene.render.shading.specular, 0.3f);
    EXPECT_EQ(scene.render.shading.shininess, 32.0f);
    EXPECT_EQ(scene.output.pattern, "/scenes/cutaway_####.exr");
    EXPECT_EQ(scene.output.pixelType, PixelType::Half);
    EXPECT_EQ(scene.output.compression, Compression::Zip);
    EXPECT_FALSE(scene.output.png);
}

TEST(SceneParser, ReadsEveryKeyIntoItsField) {
    const json document = json::parse(kFullExample);
    const Scene scene = parseScene(document, "/data/scenes");
    EXPECT_EQ(scene.document, document);
    EXPECT_EQ(scene.volume.phantom, "head");
    EXPECT_EQ(scene.volume.phantomSize, glm::ivec3(128, 96, 64));
    EXPECT_EQ(scene.volume.spacing, glm::dvec3(0.5, 0.5, 2));
    ASSERT_TRUE(scene.volume.window.has_value());
    EXPECT_EQ((*scene.volume.window)[0], 10.0);
    EXPECT_EQ((*scene.volume.window)[1], 240.0);
    ASSERT_EQ(scene.transfer.points.size(), 4u);
    EXPECT_EQ(scene.transfer.points[2].value, 90.0);
    EXPECT_EQ(scene.transfer.points[2].color, glm::vec3(0.9f, 0.6f, 0.5f));
    EXPECT_EQ(scene.transfer.points[2].alpha, 0.05f);
    EXPECT_EQ(scene.transfer.points[3].value, 200.0);
    EXPECT_EQ(scene.camera.projection, Projection::Orthographic);
    EXPECT_EQ(scene.camera.fovDeg, 45.0);
    EXPECT_EQ(scene.camera.orthoHeight, 300.0);
    EXPECT_TRUE(scene.camera.useOrbit);
    EXPECT_EQ(scene.camera.azimuthDeg, 30.0);
    EXPECT_EQ(scene.camera.elevationDeg, 15.0);
    EXPECT_EQ(scene.camera.distance, 700.0);
    EXPECT_EQ(scene.camera.target, glm::dvec3(1, 2, 3));
    EXPECT_EQ(scene.camera.up, glm::dvec3(0, 1, 0));
    EXPECT_EQ(scene.lights.ambient, 0.1f);
    EXPECT_EQ(scene.lights.headlight, 2.0f);
    ASSERT_EQ(scene.lights.directional.size(), 2u);
    EXPECT_EQ(scene.lights.directional[0].direction, glm::dvec3(-1, 1, -1));
    EXPECT_EQ(scene.lights.directional[0].color, glm::vec3(1, 0.5f, 0.25f));
    EXPECT_EQ(scene.lights.directional[0].intensity, 0.4f);
    EXPECT_EQ(scene.lights.directional[1].direction, glm::dvec3(0, 0, 1));
    EXPECT_EQ(scene.lights.directional[1].color, glm::vec3(1.0f));
    EXPECT_EQ(scene.lights.directional[1].intensity, 1.0f);
    EXPECT_EQ(scene.render.width, 640);
    EXPECT_EQ(scene.render.height, 480);
    EXPECT_EQ(scene.render.sliceSpacing, 0.5);
    EXPECT_EQ(scene.render.terminationOpacity, 0.98);
    EXPECT_EQ(scene.render.background, glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
    EXPECT_FALSE(scene.render.shading.enabled);
    EXPECT_EQ(scene.render.shading.diffuse, 0.7f);
    EXPECT_EQ(scene.render.shading.specular, 0.2f);
    EXPECT_EQ(scene.render.shading.shininess, 64.0f);
    EXPECT_EQ(scene.output.pattern, "/data/scenes/out/head_####.exr");
    EXPECT_EQ(scene.output.pixelType, PixelType::Float);
    EXPECT_EQ(scene.output.compression, Compression::Piz);
    EXPECT_TRUE(scene.output.png);
}

TEST(SceneParser, DraftQualitySetsRefinesDefaultOnly) {
    const auto refineOf = [](const char* render) {
        return parseScene(patched(std::string(R"({"render": )") + render + "}"), "/scenes")
            .render.refine;
    };
    EXPECT_EQ(refineOf(R"({"quality": "draft"})"), 1);
    EXPECT_EQ(refineOf(R"({"quality": "final"})"), 4);
    EXPECT_EQ(refineOf(R"({"quality": "draft", "refine": 3})"), 3);
    EXPECT_EQ(refineOf(R"({"refine": 2, "quality": "draft"})"), 2);
}

TEST(SceneParser, ReadsCutAntialias) {
    EXPECT_EQ(parseScene(patched("{}"), "/s").render.cutAntialias, 1.0);
    EXPECT_EQ(parseScene(patched(R"({"render": {"cut_antialias": 0}})"), "/s").render.cutAntialias,
              0.0);
    EXPECT_EQ(
        parseScene(patched(R"({"render": {"cut_antialias": 2.5}})"), "/s").render.cutAntialias,
        2.5);
}

TEST(SceneParser, ReadsLookAtCamera) {
    const Scene scene = parseScene(patched(R"({"camera": {"look_at":
        {"eye": [0, -400, 100], "target": [0, 0, 10], "up": [0, 0, 1]}}})"),
                                   "/s");
    EXPECT_FALSE(scene.camera.useOrbit);
    EXPECT_EQ(scene.camera.eye, glm::dvec3(0, -400, 100));
    EXPECT_EQ(scene.camera.target, glm::dvec3(0, 0, 10));
    EXPECT_EQ(scene.camera.up, glm::dvec3(0, 0, 1));
}

TEST(SceneParser, ReadsBackgroundForms) {
    EXPECT_EQ(
        parseScene(patched(R"({"render": {"background": "transparent"}})"), "/s").render.background,
        glm::vec4(0.0f));
    EXPECT_EQ(parseScene(patched(R"({"render": {"background": [1, 0.5, 0, 0.25]}})"), "/s")
                  .render.background,
              glm::vec4(1, 0.5f, 0, 0.25f));
    EXPECT_EQ(parseError(patched(R"({"render": {"background": "black"}})")),
              "scene.json: /render/background: expected an array of 3 or 4 numbers in [0, 1], "
              "or \"transparent\", got \"black\"");
    EXPECT_EQ(parseError(patched(R"({"render": {"background": [0, 0]}})")),
              "scene.json: /render/background: expected an array of 3 or 4 numbers in [0, 1], "
              "or \"transparent\", got [0,0]");
}

TEST(SceneParser, ReadsRawFileLayoutAndResolvesPaths) {
    test::TempDir dir;
    dir.write("scenes/data/scan.raw", "xxxx");
    const Scene scene = parseScene(json::parse(R"({"version": 1,
        "volume": {"file": "data/scan.raw", "spacing": [1, 1, 3],
                   "raw": {"dims": [2, 2, 1], "type": "int16", "spacing": [0.5, 0.5, 1.5],
                           "endian": "big", "offset": 352}},
        "output": {"pattern": "../out/f_####.exr"}})"),
                                   dir.path() / "scenes");
    EXPECT_EQ(scene.volume.file, dir.path() / "scenes/data/scan.raw");
    EXPECT_TRUE(scene.volume.phantom.empty());
    ASSERT_TRUE(scene.volume.raw.has_value());
    EXPECT_EQ(scene.volume.raw->dims, glm::ivec3(2, 2, 1));
    EXPECT_EQ(scene.volume.raw->type, VoxelType::I16);
    EXPECT_EQ(scene.volume.raw->spacing, glm::dvec3(0.5, 0.5, 1.5));
    EXPECT_TRUE(scene.volume.raw->bigEndian);
    EXPECT_EQ(scene.volume.raw->offset, 352u);
    EXPECT_EQ(scene.volume.spacing, glm::dvec3(1, 1, 3));
    EXPECT_EQ(scene.output.pattern, (dir.path() / "out/f_####.exr").string());
}

TEST(SceneParser, EveryVoxelTypeNameParses) {
    test::TempDir dir;
    dir.write("scan.raw", "x");
    const std::pair<const char*, VoxelType> types[] = {
        {"uint8", VoxelType::U8},    {"int8", VoxelType::I8},    {"uint16", VoxelType::U16},
        {"int16", VoxelType::I16},   {"uint32", VoxelType::U32}, {"int32", VoxelType::I32},
        {"float32", VoxelType::F32}, {"float64", VoxelType::F64}};
    for (const auto& [name, type] : types) {
        json document = json::parse(R"({"version": 1, "volume": {"file": "scan.raw",
            "raw": {"dims": [1, 1, 1]}}})");
        document["volume"]["raw"]["type"] = name;
        EXPECT_EQ(parseScene(document, dir.path()).volume.raw->type, type) << name;
    }
    EXPECT_EQ(parseScene(json::parse(R"({"version": 1, "volume": {"file": "scan.raw",
        "raw": {"dims": [1, 1, 1], "type": "uint8"}}})"),
                         dir.path())
                  .volume.raw->bigEndian,
              false);
}

TEST(SceneParser, AbsolutePathsStayAsGiven) {
    test::TempDir dir;
    const auto file = dir.write("scan.nii.gz", "x");
    json document = patched(R"({"output": {"pattern": "/tmp/out/x_####.exr"}})");
    document["volume"] = {{"file", file.string()}};
    const Scene scene = parseScene(document, "/elsewhere");
    EXPECT_EQ(scene.volume.file, file);
    EXPECT_EQ(scene.output.pattern, "/tmp/out/x_####.exr");
}

TEST(SceneParser, ReportsEveryProblemAtOnce) {
    const std::string message = parseError(patched(R"({
        "camera": {"fov": 200},
        "render": {"size": [-5, 512]},
        "lights": {"ambient": "bright"}})"));
    const auto found = lines(message);
    ASSERT_EQ(found.size(), 3u) << message;
    EXPECT_EQ(found[0], "scene.json: /camera/fov: expected a number in (0, 170), got 200");
    EXPECT_EQ(found[1], "scene.json: /lights/ambient: expected a number in [0, 1], got \"bright\"");
    EXPECT_EQ(found[2], "scene.json: /render/size/0: expected an integer in [1, 16384], got -5");
}

TEST(SceneParser, UnknownKeysSuggestTheClosestKnownKey) {
    EXPECT_EQ(parseError(patched(R"({"camera": {"fovv": 30}})")),
              "scene.json: /camera/fovv: unknown key (did you mean \"fov\"?)");
    EXPECT_EQ(parseError(patched(R"({"rendr": {}})")),
              "scene.json: /rendr: unknown key (did you mean \"render\"?)");
    EXPECT_EQ(parseError(patched(R"({"render": {"shading": {"shinyness": 3}}})")),
              "scene.json: /render/shading/shinyness: unknown key (did you mean \"shininess\"?)");
    EXPECT_EQ(parseError(patched(R"({"camera": {"wobble": 2}})")),
              "scene.json: /camera/wobble: unknown key");
    EXPECT_EQ(parseError(patched(R"({"volume": {"phantom": "hed"}})")),
              "scene.json: /volume/phantom: expected one of \"head\", \"orange\" (did you mean "
              "\"head\"?), got \"hed\"");
}

TEST(SceneParser, VersionIsRequiredAndChecked) {
    EXPECT_EQ(parseError(patched(R"({"version": null})")),
              "scene.json: /version: missing; add \"version\": 1 at the top level of the scene");
    EXPECT_EQ(parseError(patched(R"({"version": 2})")),
              "scene.json: /version: unsupported version: expected 1, got 2");
    EXPECT_EQ(parseError(patched(R"({"version": "1"})")),
              "scene.json: /version: unsupported version: expected 1, got \"1\"");
}

TEST(SceneParser, RootMustBeAnObject) {
    EXPECT_EQ(parseError(json::parse("[1, 2]")),
              "scene.json: (root): expected an object (a scene), got [1,2]");
}

TEST(SceneParser, VolumeNeedsExactlyOneSource) {
    EXPECT_EQ(parseError(patched(R"({"volume": null})")),
              "scene.json: /volume: missing; expected an object");
    EXPECT_EQ(parseError(patched(R"({"volume": {"phantom": null, "size": [8, 8, 8]}})")),
              "scene.json: /volume: expected exactly one of \"file\" or \"phantom\", got neither");
    test::TempDir dir;
    dir.write("scan.nrrd", "x");
    EXPECT_EQ(parseError(patched(R"({"volume": {"file": "scan.nrrd"}})"), dir.path()),
              "scene.json: /volume: expected exactly one of \"file\" or \"phantom\", got both");
}

TEST(SceneParser, MissingVolumeFileNamesPointerAndPath) {
    test::TempDir dir;
    const std::string message =
        parseError(json::parse(R"({"version": 1, "volume": {"file": "../data/none.nii.gz"}})"),
                   dir.path() / "scenes");
    EXPECT_EQ(message, "scene.json: /volume/file: no such file: " +
                           (dir.path() / "data/none.nii.gz").string());
    // A folder is a DICOM series' (read, and judged, when the volume loads);
    // a headerless file's layout cannot describe one.
    EXPECT_EQ(parseError(json::parse(R"({"version": 1, "volume": {"file": "."}})"), dir.path()),
              "");
    EXPECT_EQ(parseError(json::parse(R"({"version": 1, "volume": {"file": ".",
                  "raw": {"dims": [2, 2, 2], "type": "uint8"}}})"),
                         dir.path()),
              "scene.json: /volume/file: not a regular file (it is a folder): " +
                  dir.path().string() + "/");
    // A name the system refuses to look up (found by fuzz_scene: it threw filesystem_error).
    json tooLong = json::parse(R"({"version": 1, "volume": {}})");
    tooLong["volume"]["file"] = std::string(300, 'x') + ".nrrd";
    EXPECT_EQ(parseError(tooLong, dir.path()), "scene.json: /volume/file: no such file: " +
                                                   (dir.path() / std::string(300, 'x')).string() +
                                                   ".nrrd");
}

TEST(SceneParser, HeaderlessFilesNeedARawLayout) {
    test::TempDir dir;
    dir.write("scan.raw", "x");
    EXPECT_EQ(
        parseError(json::parse(R"({"version": 1, "volume": {"file": "scan.raw"}})"), dir.path()),
        "scene.json: /volume/file: expected a .nrrd, .nhdr, .nii, .nii.gz, .mha or .mhd file, a "
        "DICOM file, folder or DICOMDIR, or a \"raw\" layout for a headerless file, got "
        "\"scan.raw\"");
    EXPECT_EQ(parseError(json::parse(R"({"version": 1, "volume": {"file": "scan.raw",
        "raw": {"dims": [1, 1, 1]}}})"),
                         dir.path()),
              "scene.json: /volume/raw/type: missing; expected one of \"uint8\", \"int8\", "
              "\"uint16\", \"int16\", \"uint32\", \"int32\", \"float32\", \"float64\"");
}

TEST(SceneParser, SizeAndRawBelongToTheirSource) {
    test::TempDir dir;
    dir.write("scan.nii", "x");
    EXPECT_EQ(parseError(json::parse(R"({"version": 1, "volume": {"file": "scan.nii",
        "size": [64, 64, 64]}})"),
                         dir.path()),
              "scene.json: /volume/size: only allowed with \"phantom\" (a file's grid comes "
              "from the file)");
    EXPECT_EQ(parseError(patched(R"({"volume": {"raw": {"dims": [1, 1, 1]}}})")),
              "scene.json: /volume/raw: only allowed with \"file\"");
}

TEST(SceneParser, WindowNeedsLoBelowHi) {
    EXPECT_EQ(parseError(patched(R"({"volume": {"window": [5, 3]}})")),
              "scene.json: /volume/window: expected [lo, hi] with lo < hi, got [5,3]");
}

TEST(SceneParser, TransferPointsIncreaseStrictly) {
    EXPECT_EQ(parseError(patched(R"({"transfer": {"points": [
        {"value": 0, "color": [0, 0, 0], "alpha": 0},
        {"value": 50, "color": [0, 0, 0], "alpha": 0},
        {"value": 120, "color": [0, 0, 0], "alpha": 0},
        {"value": 100, "color": [0, 0, 0], "alpha": 0}]}})")),
              "scene.json: /transfer/points/3/value: expected a value greater than the previous "
              "point's (120), got 100");
    EXPECT_EQ(parseError(patched(R"({"transfer": {"points": [
        {"value": 0, "color": [0, 0, 0], "alpha": 0}]}})")),
              "scene.json: /transfer/points: expected an array of at least 2 objects, got "
              "[{\"alpha\":0,\"color\":[0,0,0],\"value\":0}]");
    EXPECT_EQ(parseError(patched(R"({"transfer": {}})")),
              "scene.json: /transfer/points: missing; expected an array of at least 2 objects");
    EXPECT_EQ(parseError(patched(R"({"transfer": {"points": [
        {"value": 0, "alpha": 0}, {"value": 1, "color": [0, 0, 0], "alpha": 1}]}})")),
              "scene.json: /transfer/points/0/color: missing; expected an RGB colour: 3 numbers "
              "in [0, 1]");
}

TEST(SceneParser, CameraChecksItsGeometry) {
    EXPECT_EQ(parseError(patched(R"({"camera": {"orbit": {}, "look_at": {"eye": [0, -1, 0]}}})")),
              "scene.json: /camera: expected at most one of \"orbit\" or \"look_at\", got both");
    EXPECT_EQ(parseError(patched(R"({"camera": {"look_at": {"eye": [1, 2, 3],
        "target": [1, 2, 3]}}})")),
              "scene.json: /camera/look_at/eye: expected a point different from target [1, 2, "
              "3], got [1,2,3]");
    EXPECT_EQ(parseError(patched(R"({"camera": {"look_at": {"eye": [0, 0, 500]}}})")),
              "scene.json: /camera/look_at/up: expected a direction not parallel to the view "
              "direction (target - eye = [0, 0, -500]), got [0,0,1]");
    EXPECT_EQ(parseError(patched(R"({"camera": {"look_at": {"eye": [0, 0, 500],
        "up": [0, 0, -2]}}})")),
              "scene.json: /camera/look_at/up: expected a direction not parallel to the view "
              "direction (target - eye = [0, 0, -500]), got [0,0,-2]");
    EXPECT_EQ(parseError(patched(R"({"camera": {"look_at": {"target": [0, 0, 0]}}})")),
              "scene.json: /camera/look_at/eye: missing; expected an array of 3 numbers in "
              "[-1000000, 1000000]");
    EXPECT_EQ(parseError(patched(R"({"camera": {"orbit": {"up": [0, 0, 0]}}})")),
              "scene.json: /camera/orbit/up: expected a non-zero direction, got [0,0,0]");
    EXPECT_EQ(parseError(patched(R"({"camera": {"projection": "fisheye"}})")),
              "scene.json: /camera/projection: expected one of \"perspective\", "
              "\"orthographic\", got \"fisheye\"");
}

TEST(SceneParser, LightsAreLimited) {
    EXPECT_EQ(parseError(patched(R"({"lights": {"directional": [{"direction": [0, 0, 0]}]}})")),
              "scene.json: /lights/directional/0/direction: expected a non-zero direction, got "
              "[0,0,0]");
    EXPECT_EQ(parseError(patched(R"({"lights": {"directional": [{"intensity": 1}]}})")),
              "scene.json: /lights/directional/0/direction: missing; expected an array of 3 "
              "numbers in [-1000000, 1000000]");
}

TEST(SceneParser, OutputIsChecked) {
    EXPECT_EQ(parseError(patched(R"({"output": {"pattern": ""}})")),
              "scene.json: /output/pattern: expected a non-empty string, got \"\"");
    EXPECT_EQ(parseError(patched(R"({"output": {"pixel_type": "double", "png": "yes"}})")),
              "scene.json: /output/pixel_type: expected one of \"half\", \"float\", got "
              "\"double\"\nscene.json: /output/png: expected true or false, got \"yes\"");
    EXPECT_EQ(parseError(patched(R"({"output": {"compression": "dwaa"}})")),
              "scene.json: /output/compression: expected one of \"none\", \"rle\", \"zips\", "
              "\"zip\", \"piz\", got \"dwaa\"");
}

TEST(SceneParser, LongValuesAreAbbreviated) {
    const std::string message = parseError(
        patched(R"({"camera": {"fov": "a very long string that goes on and on and on and on"}})"));
    EXPECT_EQ(message, "scene.json: /camera/fov: expected a number in (0, 170), got \"a very "
                       "long string that goes on and ...");
}

TEST(SceneParser, SectionsMustBeObjects) {
    EXPECT_EQ(parseError(patched(R"({"camera": [1, 2, 3]})")),
              "scene.json: /camera: expected an object, got [1,2,3]");
    EXPECT_EQ(parseError(patched(R"({"lights": {"directional": {}}})")),
              "scene.json: /lights/directional: expected an array of at most 4 objects, got {}");
}

} // namespace
} // namespace cutaway
