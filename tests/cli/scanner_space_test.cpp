// Placements in a scan's own coordinates ("space": "lps" or "ras") through
// the binary: on a scan whose index axes are permuted and mirrored against
// LPS, a peeler and a look-at camera given in LPS or RAS render bit for bit
// as the same ones given in the volume frame. The test maps the placements
// itself, from the scan's geometry (origin + direction * spacing * index, the
// volume frame centred on the grid), with numbers that map exactly.
#include "cli_util.hpp"
#include "io/exr.hpp"
#include "volume/phantom.hpp"
#include "volume/volume.hpp"

#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

const glm::ivec3 kDims{24, 20, 16};
const glm::dvec3 kSpacing{1.0, 1.0, 2.0};
const glm::dvec3 kOrigin{10.0, -20.0, 35.0};
// Columns: index axis i runs along +y, j along -x, k along -z (det -1).
const glm::dmat3 kDirection(0, 1, 0, -1, 0, 0, 0, 0, -1);
const glm::dmat4 kRasFromLps = glm::scale(glm::dmat4(1.0), glm::dvec3(-1.0, -1.0, 1.0));

// The map from the volume frame to LPS, written out from the geometry.
glm::dmat4 lpsFromVolume() {
    const glm::dvec3 corner = 0.5 * glm::dvec3(kDims) * kSpacing - 0.5 * kSpacing;
    return glm::translate(glm::dmat4(1.0), kOrigin) * glm::dmat4(kDirection) *
           glm::translate(glm::dmat4(1.0), corner);
}

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

std::string vec3(glm::dvec3 v) {
    std::string text(1, '['); // appended: GCC 12's false -Wrestrict (its bug 105329)
    text += number(v.x);
    text += ", ";
    text += number(v.y);
    text += ", ";
    text += number(v.z);
    text += ']';
    return text;
}

std::string matrix(const glm::dmat4& m) {
    std::string text = "[";
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            text += number(m[col][row]) + (row == 3 && col == 3 ? "]" : ", ");
    return text;
}

class ScannerSpace : public CliTest {
protected:
    void SetUp() override {
        CliTest::SetUp();
        Volume scan = makePhantom("head", kDims, kSpacing).values;
        scan.space = Space::LPS;
        scan.origin = kOrigin;
        scan.direction = kDirection;
        writeNrrd(m_dir / "scan.nrrd", scan);
    }

    // The scene with a peeler placed by `box` and a camera at `eye` looking
    // at `target` with `up`, all in `space`.
    fs::path scene(const std::string& name, const std::string& space, const glm::dmat4& box,
                   glm::dvec3 eye, glm::dvec3 target, glm::dvec3 up) {
        return write(name, R"({"version": 1, "volume": {"file": "scan.nrrd"},
            "transfer": {"points": [{"value": 0.1, "color": [1, 0.8, 0.6], "alpha": 0},
                                    {"value": 0.3, "color": [1, 0.8, 0.6], "alpha": 0.6},
                                    {"value": 1, "color": [1, 1, 1], "alpha": 1}]},
            "camera": {"look_at": {"space": ")" +
                               space + R"(", "eye": )" + vec3(eye) + R"(, "target": )" +
                               vec3(target) + R"(, "up": )" + vec3(up) +
                               R"(}},
            "operators": [{"type": "peeler", "placement": {"space": ")" +
                               space + R"(", "matrix": )" + matrix(box) + R"(},
                           "params": {"angle": 70}}],
            "render": {"size": [40, 40]}})");
    }

    Image render(const fs::path& sceneFile, const std::string& name) {
        const CommandResult r = runCutaway("render " + sceneFile.string() + " -o " +
                                           (m_dir / (name + "_#.exr")).string());
        EXPECT_EQ(r.code, 0) << r.output;
        return readExr(m_dir / (name + "_0.exr"));
    }
};

TEST_F(ScannerSpace, LpsAndRasPlacementsRenderAsTheVolumeFrameOnes) {
    // In the volume frame: a box over the phantom's top, turned 30 degrees.
    const glm::dmat4 box =
        glm::scale(glm::rotate(glm::translate(glm::dmat4(1.0), {1.5, -2.0, 10.5}),
                               glm::radians(30.0), glm::dvec3(0, 0, 1)),
                   glm::dvec3(8.0, 6.0, 6.0));
    const glm::dvec3 eye(20.5, -60.0, 30.0), target(0.5, 0.0, 2.0), up(0.0, 0.0, 1.0);
    const glm::dmat4 toLps = lpsFromVolume();
    const auto point = [](const glm::dmat4& m, glm::dvec3 p) {
        return glm::dvec3(m * glm::dvec4(p, 1.0));
    };
    const auto direction = [](const glm::dmat4& m, glm::dvec3 d) { return glm::dmat3(m) * d; };
    const Image reference = render(scene("v.json", "volume", box, eye, target, up), "v");

    const glm::dmat4 toRas = kRasFromLps * toLps;
    for (const auto& [space, to] : {std::pair{"lps", toLps}, std::pair{"ras", toRas}}) {
        SCOPED_TRACE(space);
        const Image image = render(scene(std::string(space) + ".json", space, to * box,
                                         point(to, eye), point(to, target), direction(to, up)),
                                   space);
        EXPECT_EQ(image.rgba, reference.rgba) << "the same picture, bit for bit";
    }
    // Control: the LPS numbers read as the volume frame's are another picture.
    const Image control = render(scene("c.json", "volume", toLps * box, point(toLps, eye),
                                       point(toLps, target), direction(toLps, up)),
                                 "c");
    EXPECT_NE(control.rgba, reference.rgba);
    float sum = 0.0f;
    for (const float v : reference.rgba)
        sum += v;
    EXPECT_GT(sum, 20.0f) << "the reference shows the head";
}

// An orbit around a target given in RAS: its azimuth and elevation turn about
// an `up` in RAS. Against the look-at at the same eye (to float rounding).
TEST_F(ScannerSpace, AnOrbitInRasTurnsAboutItsOwnAxes) {
    const glm::dmat4 toRas = kRasFromLps * lpsFromVolume();
    const glm::dvec3 targetRas(toRas * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    // Azimuth 90 puts the eye on +x of RAS (the patient's right), at 80 mm.
    const fs::path orbit = write("o.json", R"({"version": 1, "volume": {"file": "scan.nrrd"},
        "camera": {"orbit": {"space": "ras", "azimuth": 90, "distance": 80, "target": )" +
                                               vec3(targetRas) + R"(}},
        "render": {"size": [32, 32]}})");
    const fs::path lookAt = write("l.json", R"({"version": 1, "volume": {"file": "scan.nrrd"},
        "camera": {"look_at": {"space": "ras", "eye": )" +
                                                vec3(targetRas + glm::dvec3(80, 0, 0)) +
                                                R"(, "target": )" + vec3(targetRas) + R"(}},
        "render": {"size": [32, 32]}})");
    const Image a = render(orbit, "o"), b = render(lookAt, "l");
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
        worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]));
    EXPECT_LT(worst, 2e-3f);
    // Control: the same orbit in the volume frame looks from elsewhere.
    const fs::path inVolume = write("ov.json", R"({"version": 1, "volume": {"file": "scan.nrrd"},
        "camera": {"orbit": {"azimuth": 90, "distance": 80}}, "render": {"size": [32, 32]}})");
    const Image c = render(inVolume, "ov");
    float control = 0.0f;
    for (std::size_t i = 0; i < c.rgba.size(); ++i)
        control = std::max(control, std::abs(c.rgba[i] - b.rgba[i]));
    EXPECT_GT(control, 0.05f);
}

// A scan without patient coordinates cannot place anything in them: exit 2
// naming the pointer, from validate and render alike, and nothing written.
TEST_F(ScannerSpace, AScanWithoutPatientCoordinatesRefusesThem) {
    writeNrrd(m_dir / "bare.nrrd", makePhantom("head", kDims).values);
    const fs::path bad = write("bad.json", R"({"version": 1, "volume": {"file": "bare.nrrd"},
        "operators": [{"type": "retractor", "placement": {"space": "ras", "scale": [8, 8, 8]}}],
        "render": {"size": [16, 16]}, "output": {"pattern": "out/f_#.exr"}})");
    for (const char* command : {"validate", "render"}) {
        const CommandResult r = runCutaway(std::string(command) + " " + bad.string());
        EXPECT_EQ(r.code, 2) << r.output;
        EXPECT_NE(r.output.find("/operators/0/placement/space: \"ras\" needs the scan's patient "
                                "coordinates"),
                  std::string::npos)
            << r.output;
    }
    EXPECT_FALSE(fs::exists(m_dir / "out"));
    const fs::path attached = write("attached.json", R"({"version": 1,
        "volume": {"phantom": "head", "size": [16, 16, 16]},
        "operators": [{"type": "retractor", "placement": {"scale": [8, 8, 8]}}],
        "meshes": [{"file": "none.gltf", "attach": 0, "placement": {"space": "lps"}}]})");
    const CommandResult r = runCutaway("validate " + attached.string());
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("/meshes/0/placement/space: an attached mesh"), std::string::npos)
        << r.output;
}

} // namespace
} // namespace cutaway::test
