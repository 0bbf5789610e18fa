// Every range boundary of the scene format: just inside parses, just outside
// gives exactly one error naming the key's JSON pointer.
#include "scene/scene_test_util.hpp"

#include <gtest/gtest.h>

namespace cutaway {
namespace {

using test::lines;
using test::parseError;
using test::patched;

struct Boundary {
    const char* patch;   ///< merge patch over the minimal scene
    const char* pointer; ///< where the error must be; nullptr: must parse
};

void PrintTo(const Boundary& boundary, std::ostream* os) {
    *os << boundary.patch;
}

class SceneRanges : public ::testing::TestWithParam<Boundary> {};

TEST_P(SceneRanges, BoundaryIsEnforced) {
    const Boundary& boundary = GetParam();
    const std::string message = parseError(patched(boundary.patch));
    if (boundary.pointer == nullptr) {
        EXPECT_EQ(message, "") << boundary.patch;
        return;
    }
    const auto found = lines(message);
    ASSERT_EQ(found.size(), 1u) << boundary.patch << "\n" << message;
    EXPECT_EQ(found[0].rfind(std::string("scene.json: ") + boundary.pointer + ": expected ", 0), 0u)
        << boundary.patch << "\n"
        << message;
}

std::string join(const char* a, const char* b) {
    return std::string(a) + b;
}

// clang-format off
const Boundary kBoundaries[] = {
    // /volume
    {R"({"volume": {"size": [8, 1024, 8]}})", nullptr},
    {R"({"volume": {"size": [7, 8, 8]}})", "/volume/size/0"},
    {R"({"volume": {"size": [8, 8, 1025]}})", "/volume/size/2"},
    {R"({"volume": {"size": [8, 8]}})", "/volume/size"},
    {R"({"volume": {"size": [8, 8.5, 8]}})", "/volume/size/1"},
    {R"({"volume": {"spacing": [1e-9, 1e4, 1]}})", nullptr},
    {R"({"volume": {"spacing": [0, 1, 1]}})", "/volume/spacing/0"},
    {R"({"volume": {"spacing": [1, 10000.001, 1]}})", "/volume/spacing/1"},
    {R"({"volume": {"spacing": [1, 1, 1e300]}})", "/volume/spacing/2"},
    {R"({"volume": {"window": [-1e30, 1e30]}})", nullptr},
    {R"({"volume": {"window": [0, 0.001]}})", nullptr},
    {R"({"volume": {"window": [1, 1]}})", "/volume/window"},
    {R"({"volume": {"window": [-1e31, 0]}})", "/volume/window/0"},
    {R"({"volume": {"window": [0, 1, 2]}})", "/volume/window"},
    {R"({"volume": {"phantom": "orange"}})", nullptr},
    {R"({"volume": {"phantom": 3}})", "/volume/phantom"},
    // /transfer
    {R"({"transfer": {"points": [{"value": 0, "color": [0, 0, 0], "alpha": 0},
        {"value": 1e-9, "color": [1, 1, 1], "alpha": 1}]}})", nullptr},
    {R"({"transfer": {"points": [{"value": -1e30, "color": [0, 0, 0], "alpha": 0},
        {"value": 1e30, "color": [1, 1, 1], "alpha": 1}]}})", nullptr},
    {R"({"transfer": {"points": [{"value": 0, "color": [0, 0, 0], "alpha": -0.01},
        {"value": 1, "color": [1, 1, 1], "alpha": 1}]}})", "/transfer/points/0/alpha"},
    {R"({"transfer": {"points": [{"value": 0, "color": [0, 0, 0], "alpha": 0},
        {"value": 1, "color": [1, 1, 1], "alpha": 1.01}]}})", "/transfer/points/1/alpha"},
    {R"({"transfer": {"points": [{"value": 0, "color": [0, 0, 0], "alpha": 0},
        {"value": 1, "color": [1, 1.01, 1], "alpha": 1}]}})", "/transfer/points/1/color/1"},
    {R"({"transfer": {"points": [{"value": 0, "color": [0, 0, -0.01], "alpha": 0},
        {"value": 1, "color": [1, 1, 1], "alpha": 1}]}})", "/transfer/points/0/color/2"},
    {R"({"transfer": {"points": [{"value": 1, "color": [0, 0, 0], "alpha": 0},
        {"value": 1, "color": [1, 1, 1], "alpha": 1}]}})", "/transfer/points/1/value"},
    {R"({"transfer": {"points": [{"value": 0, "color": [0, 0, 0], "alpha": 0},
        {"value": 2e30, "color": [1, 1, 1], "alpha": 1}]}})", "/transfer/points/1/value"},
    // /camera
    {R"({"camera": {"fov": 0.001}})", nullptr},
    {R"({"camera": {"fov": 169.999}})", nullptr},
    {R"({"camera": {"fov": 0}})", "/camera/fov"},
    {R"({"camera": {"fov": 170}})", "/camera/fov"},
    {R"({"camera": {"ortho_height": 0}})", nullptr},
    {R"({"camera": {"ortho_height": 1e6}})", nullptr},
    {R"({"camera": {"ortho_height": -0.001}})", "/camera/ortho_height"},
    {R"({"camera": {"ortho_height": 1e300}})", "/camera/ortho_height"},
    {R"({"camera": {"orbit": {"azimuth": -36000}}})", nullptr},
    {R"({"camera": {"orbit": {"azimuth": 36000}}})", nullptr},
    {R"({"camera": {"orbit": {"azimuth": 36000.5}}})", "/camera/orbit/azimuth"},
    {R"({"camera": {"orbit": {"azimuth": -36001}}})", "/camera/orbit/azimuth"},
    {R"({"camera": {"orbit": {"elevation": 89.999}}})", nullptr},
    {R"({"camera": {"orbit": {"elevation": -89.999}}})", nullptr},
    {R"({"camera": {"orbit": {"elevation": 90}}})", "/camera/orbit/elevation"},
    {R"({"camera": {"orbit": {"elevation": -90}}})", "/camera/orbit/elevation"},
    {R"({"camera": {"orbit": {"distance": 0}}})", nullptr},
    {R"({"camera": {"orbit": {"distance": -1}}})", "/camera/orbit/distance"},
    {R"({"camera": {"orbit": {"distance": 1e7}}})", "/camera/orbit/distance"},
    {R"({"camera": {"orbit": {"target": [1e6, -1e6, 0]}}})", nullptr},
    {R"({"camera": {"orbit": {"target": [0, 2e6, 0]}}})", "/camera/orbit/target/1"},
    {R"({"camera": {"orbit": {"up": [0, 1e-6, 0]}}})", nullptr},
    {R"({"camera": {"orbit": {"up": "z"}}})", "/camera/orbit/up"},
    {R"({"camera": {"look_at": {"eye": [0, -1, 0], "up": [0, 0.001, 1]}}})", nullptr},
    {R"({"camera": {"look_at": {"eye": [0, -1, 0], "up": [0, 1, 0]}}})", "/camera/look_at/up"},
    {R"({"camera": {"look_at": {"eye": [0, 0, 0]}}})", "/camera/look_at/eye"},
    {R"({"camera": {"look_at": {"eye": [0, 0, "1"]}}})", "/camera/look_at/eye/2"},
    {R"({"camera": {"projection": "orthographic"}})", nullptr},
    // /lights
    {R"({"lights": {"ambient": 0, "headlight": 0}})", nullptr},
    {R"({"lights": {"ambient": 1, "headlight": 10}})", nullptr},
    {R"({"lights": {"ambient": -0.01}})", "/lights/ambient"},
    {R"({"lights": {"ambient": 1.01}})", "/lights/ambient"},
    {R"({"lights": {"headlight": -0.01}})", "/lights/headlight"},
    {R"({"lights": {"headlight": 10.01}})", "/lights/headlight"},
    {R"({"lights": {"directional": [{"direction": [0, 0, -1], "intensity": 0},
        {"direction": [0, 0, -1], "intensity": 10}, {"direction": [0, 0, -1]},
        {"direction": [0, 0, -1], "color": [0, 1, 0]}]}})", nullptr},
    {R"({"lights": {"directional": [{"direction": [0, 0, -1]}, {"direction": [0, 0, -1]},
        {"direction": [0, 0, -1]}, {"direction": [0, 0, -1]}, {"direction": [0, 0, -1]}]}})",
     "/lights/directional"},
    {R"({"lights": {"directional": [{"direction": [0, 0, -1], "intensity": 10.01}]}})",
     "/lights/directional/0/intensity"},
    {R"({"lights": {"directional": [{"direction": [0, 0, -1], "intensity": -0.01}]}})",
     "/lights/directional/0/intensity"},
    {R"({"lights": {"directional": [{"direction": [0, 0, -1], "color": [2, 0, 0]}]}})",
     "/lights/directional/0/color/0"},
    // /render
    {R"({"render": {"size": [1, 16384]}})", nullptr},
    {R"({"render": {"size": [0, 512]}})", "/render/size/0"},
    {R"({"render": {"size": [512, 16385]}})", "/render/size/1"},
    {R"({"render": {"size": [512]}})", "/render/size"},
    {R"({"render": {"size": [512.0, 512]}})", nullptr},
    {R"({"render": {"slice_spacing": 0.05}})", nullptr},
    {R"({"render": {"slice_spacing": 16}})", nullptr},
    {R"({"render": {"slice_spacing": 0.049}})", "/render/slice_spacing"},
    {R"({"render": {"slice_spacing": 16.01}})", "/render/slice_spacing"},
    {R"({"render": {"slice_spacing": 1e308}})", "/render/slice_spacing"},
    {R"({"render": {"termination_opacity": 0.5}})", nullptr},
    {R"({"render": {"termination_opacity": 1}})", nullptr},
    {R"({"render": {"termination_opacity": 0.49}})", "/render/termination_opacity"},
    {R"({"render": {"termination_opacity": 1.001}})", "/render/termination_opacity"},
    {R"({"render": {"filter": "linear"}})", nullptr},
    {R"({"render": {"filter": "cubic"}})", nullptr},
    {R"({"render": {"filter": "bicubic"}})", "/render/filter"},
    {R"({"render": {"filter": true}})", "/render/filter"},
    {R"({"transfer": {"points": [{"value": 0, "color": [0, 0, 0], "alpha": 0},
        {"value": 1, "color": [1, 1, 1], "alpha": 1}], "unit_distance": 0.5}})",
     nullptr},
    {R"({"transfer": {"points": [{"value": 0, "color": [0, 0, 0], "alpha": 0},
        {"value": 1, "color": [1, 1, 1], "alpha": 1}], "unit_distance": 0}})",
     "/transfer/unit_distance"},
    {R"({"render": {"refine": 1}})", nullptr},
    {R"({"render": {"refine": 8}})", nullptr},
    {R"({"render": {"refine": 0}})", "/render/refine"},
    {R"({"render": {"refine": 9}})", "/render/refine"},
    {R"({"render": {"refine": 2.5}})", "/render/refine"},
    {R"({"render": {"quality": "draft"}})", nullptr},
    {R"({"render": {"quality": "final"}})", nullptr},
    {R"({"render": {"quality": "fast"}})", "/render/quality"},
    {R"({"render": {"quality": 1}})", "/render/quality"},
    {R"({"render": {"background": [0, 0, 0]}})", nullptr},
    {R"({"render": {"background": [1, 1, 1, 0]}})", nullptr},
    {R"({"render": {"background": [1, 1, 1, 1.01]}})", "/render/background/3"},
    {R"({"render": {"background": [-0.01, 0, 0]}})", "/render/background/0"},
    {R"({"render": {"background": [0, 0, 0, 0, 0]}})", "/render/background"},
    {R"({"render": {"shading": {"diffuse": 0, "specular": 1, "shininess": 1}}})", nullptr},
    {R"({"render": {"shading": {"diffuse": 1, "specular": 0, "shininess": 512}}})", nullptr},
    {R"({"render": {"shading": {"diffuse": 1.01}}})", "/render/shading/diffuse"},
    {R"({"render": {"shading": {"specular": -0.01}}})", "/render/shading/specular"},
    {R"({"render": {"shading": {"shininess": 0.99}}})", "/render/shading/shininess"},
    {R"({"render": {"shading": {"shininess": 512.01}}})", "/render/shading/shininess"},
    {R"({"render": {"shading": {"enabled": 1}}})", "/render/shading/enabled"},
    // /output
    {R"({"output": {"pattern": "x.exr", "pixel_type": "float", "png": false}})", nullptr},
    {R"({"output": {"pattern": 5}})", "/output/pattern"},
    {R"({"output": {"pixel_type": "Half"}})", "/output/pixel_type"},
    {R"({"output": {"compression": "none"}})", nullptr},
    {R"({"output": {"compression": "ZIP"}})", "/output/compression"},
    {R"({"output": {"compression": 3}})", "/output/compression"},
};
// clang-format on

INSTANTIATE_TEST_SUITE_P(Scene, SceneRanges, ::testing::ValuesIn(kBoundaries));

// The raw layout needs a file on disk, so its boundaries are checked here.
TEST(SceneRawRanges, BoundariesAreEnforced) {
    test::TempDir dir;
    dir.write("scan.raw", "x");
    const auto check = [&](const std::string& raw, const char* pointer) {
        const auto document = nlohmann::json::parse(
            R"({"version": 1, "volume": {"file": "scan.raw", "raw": )" + raw + "}}");
        const std::string message = parseError(document, dir.path());
        if (pointer == nullptr) {
            EXPECT_EQ(message, "") << raw;
            return;
        }
        const auto found = lines(message);
        ASSERT_EQ(found.size(), 1u) << raw << "\n" << message;
        EXPECT_EQ(found[0].rfind(join("scene.json: ", pointer) + ": expected ", 0), 0u)
            << raw << "\n"
            << message;
    };
    check(R"({"dims": [1, 1, 65536], "type": "uint8", "offset": 0})", nullptr);
    check(R"({"dims": [0, 1, 1], "type": "uint8"})", "/volume/raw/dims/0");
    check(R"({"dims": [1, 65537, 1], "type": "uint8"})", "/volume/raw/dims/1");
    check(R"({"dims": [1, 1, 1], "type": "uint8", "offset": -1})", "/volume/raw/offset");
    check(R"({"dims": [1, 1, 1], "type": "uint8", "offset": 9007199254740993})", nullptr);
    check(R"({"dims": [1, 1, 1], "type": "u8"})", "/volume/raw/type");
    check(R"({"dims": [1, 1, 1], "type": "uint8", "endian": "middle"})", "/volume/raw/endian");
    check(R"({"dims": [1, 1, 1], "type": "uint8", "spacing": [1, 0, 1]})", "/volume/raw/spacing/1");
}

} // namespace
} // namespace cutaway
