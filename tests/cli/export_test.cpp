// `cutaway export`: the deformed volume resampled for other tools.
#include "cli_util.hpp"
#include "job/export_volume.hpp"
#include "operators/deformed_volume.hpp"
#include "scene/scene.hpp"
#include "volume/phantom.hpp"

#include <array>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <optional>

namespace cutaway::test {
namespace {

Scene withOperators(const std::string& operators) {
    return parseScene(nlohmann::json::parse(R"({"version": 1, "volume": {"phantom": "head"},
        "operators": )" + operators + "}"),
                      "/nonexistent", "export test");
}

// An oblique LPS orientation: the index axes rotated by 50 degrees about x,
// then by 30 about z, with j flipped; so that no axis is a space axis.
glm::dmat3 obliqueDirections() {
    const double cx = std::cos(glm::radians(50.0)), sx = std::sin(glm::radians(50.0));
    const double cz = std::cos(glm::radians(30.0)), sz = std::sin(glm::radians(30.0));
    const glm::dmat3 rx(glm::dvec3(1, 0, 0), glm::dvec3(0, cx, sx), glm::dvec3(0, -sx, cx));
    const glm::dmat3 rz(glm::dvec3(cz, sz, 0), glm::dvec3(-sz, cz, 0), glm::dvec3(0, 0, 1));
    const glm::dmat3 flipJ(glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1));
    return rz * rx * flipJ;
}

// The orange phantom with anisotropic voxels, placed obliquely in LPS.
Phantom orientedOrange() {
    Phantom p = makePhantom("orange", {40, 40, 40}, {1.0, 1.25, 0.8});
    p.values.direction = obliqueDirections();
    p.values.origin = {-31.5, 87.25, -12.0};
    p.values.space = Space::LPS;
    return p;
}

// Where the centre of voxel `voxel` lies, from a volume's header fields:
// origin + D * (spacing * index).
glm::dvec3 physical(const Volume& v, glm::ivec3 voxel) {
    return v.origin + v.direction * (v.spacing * glm::dvec3(voxel));
}

// Checks that the centre of every voxel of `scan` is the centre of a voxel of
// `out`, the same shift of indices for all, and that voxels from slice
// `untouchedFromZ` of the scan on keep their values there. Returns the shift
// (out's index of the scan's voxel (0,0,0)).
glm::ivec3 expectScanVoxelsInPlace(const Volume& scan, const Volume& out, int untouchedFromZ) {
    EXPECT_EQ(out.space, scan.space);
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(out.spacing[a], scan.spacing[a], 1e-12) << a;
    const glm::dmat3 inverse = glm::inverse(out.direction);
    std::optional<glm::ivec3> shift;
    int compared = 0;
    for (int z = 0; z < scan.dims.z; ++z)
        for (int y = 0; y < scan.dims.y; ++y)
            for (int x = 0; x < scan.dims.x; ++x) {
                const glm::ivec3 voxel(x, y, z);
                const glm::dvec3 p = physical(scan, voxel);
                const glm::dvec3 e = (inverse * (p - out.origin)) / out.spacing;
                const glm::ivec3 nearest(glm::round(e));
                if (glm::distance(e, glm::dvec3(nearest)) > 1e-6) {
                    ADD_FAILURE() << "scan voxel " << x << ' ' << y << ' ' << z
                                  << " is not on the export's grid: index " << e.x << ' ' << e.y
                                  << ' ' << e.z;
                    return shift.value_or(glm::ivec3(0));
                }
                if (!shift) shift = nearest - voxel;
                if (nearest - voxel != *shift || glm::any(glm::lessThan(nearest, glm::ivec3(0))) ||
                    glm::any(glm::greaterThanEqual(nearest, out.dims))) {
                    ADD_FAILURE() << "scan voxel " << x << ' ' << y << ' ' << z
                                  << " moved to export voxel " << nearest.x << ' ' << nearest.y
                                  << ' ' << nearest.z;
                    return *shift;
                }
                if (z >= untouchedFromZ) {
                    ++compared;
                    if (std::abs(out.value(nearest.x, nearest.y, nearest.z) - scan.value(x, y, z)) >
                        1e-3) {
                        ADD_FAILURE() << "scan voxel " << x << ' ' << y << ' ' << z << ": "
                                      << scan.value(x, y, z) << ", in the export "
                                      << out.value(nearest.x, nearest.y, nearest.z);
                        return *shift;
                    }
                }
            }
    EXPECT_GT(compared, 0);
    return shift.value_or(glm::ivec3(0));
}

// A peeler on the scan's bottom (index -z face, the box rotated upside down)
// and reaching out past its -x face: the flap lifts below the scan, so the
// grid grows at its low end along i and k, and its voxel (0,0,0) moves off
// the scan's. The scan's extent is 40 x 50 x 32 mm.
const char* kGrowingPeeler = R"([ { "type": "peeler",
    "placement": { "translate": [-8, 0, -8], "rotate": [180, 0, 0], "scale": [36, 30, 16] },
    "params": { "hinge": -6, "thickness": 5, "radius": 3, "angle": 160 } } ])";

} // namespace

TEST(DeformedVolume, WithoutOperatorsItIsTheVolume) {
    const Volume v = makePhantom("head", {24, 20, 16}, {1.0, 1.5, 2.0}).values;
    const Volume out = operators::resampleDeformed(operators::centred(v), {}, -1.0f).volume;
    ASSERT_EQ(out.dims, v.dims);
    EXPECT_EQ(out.type, VoxelType::F32);
    EXPECT_EQ(out.spacing, v.spacing);
    for (std::size_t i = 0; i < v.voxelCount(); ++i)
        ASSERT_NEAR(out.value(i), v.value(i), 1e-3) << i;
}

TEST(DeformedVolume, RetractorOpeningIsEmptyAndTheRestUntouched) {
    const Volume v = makePhantom("head", {48, 48, 48}).values;
    // Incision along y at x = 0 through the top 20 mm of the head.
    const Scene s = withOperators(R"([{ "type": "retractor",
        "placement": { "translate": [0, 0, 14], "scale": [30, 40, 20] },
        "params": { "length": 40, "depth": 20, "opening": 12 } }])");
    const Volume out =
        operators::resampleDeformed(operators::centred(v), s.operators, -1.0f).volume;
    ASSERT_EQ(out.dims, v.dims); // a retractor's box keeps its faces
    // Voxels x = 23, 24 (world x = -0.5, +0.5 mm) at y = 24 (y = +0.5 mm): the
    // column along the incision, in its upper half (world z 12 to 20 mm),
    // where the opening is wider than a voxel (it narrows to nothing at the
    // incision's bottom, z = 4 mm).
    int opened = 0, tissueBefore = 0;
    for (int z = 36; z < 44; ++z) {
        for (int x : {23, 24}) {
            if (v.value(x, 24, z) > 40.0) ++tissueBefore;
            if (out.value(x, 24, z) == -1.0) ++opened;
        }
    }
    EXPECT_GT(tissueBefore, 8) << "control: the column holds tissue";
    EXPECT_GE(opened, tissueBefore) << "the opening must be empty";
    // Outside the operator's box nothing moves.
    for (int z = 0; z < 20; ++z)
        for (int x = 0; x < 48; x += 5)
            EXPECT_NEAR(out.value(x, 24, z), v.value(x, 24, z), 1e-3);
}

TEST(DeformedVolume, ALiftedFlapGrowsTheGrid) {
    const Volume v = makePhantom("orange", {40, 40, 40}).values;
    // A peeler whose box reaches the top of the volume: the flap rises above it.
    const Scene s = withOperators(R"([{ "type": "peeler",
        "placement": { "translate": [0, 0, 12], "scale": [36, 30, 16] },
        "params": { "hinge": -6, "thickness": 5, "radius": 3, "angle": 160 } }])");
    const Volume out = operators::resampleDeformed(operators::centred(v), s.operators, 0.0f).volume;
    EXPECT_GT(out.dims.z, v.dims.z);
    EXPECT_EQ(out.origin.z, v.origin.z) << "the grid grows upward only";
    double above = 0.0;
    for (int z = v.dims.z; z < out.dims.z; ++z)
        for (int y = 0; y < out.dims.y; ++y)
            for (int x = 0; x < out.dims.x; ++x)
                above = std::max(above, out.value(x, y, z));
    EXPECT_GT(above, 100.0) << "the flap's rind lies above the original box";
}

// An operator whose own box misses the volume moves nothing and does not
// grow the grid (it used to stretch it to reach the operator: a 32^3 scan
// with a retractor 100 m away exported 100024 x 32 x 32 voxels); one that
// reaches the volume still does.
TEST(DeformedVolume, AnOperatorOutsideTheVolumeDoesNotGrowTheGrid) {
    const Volume v = makePhantom("orange", {40, 40, 40}).values;
    const std::string flap = R"({ "type": "peeler",
        "placement": { "translate": [0, 0, 12], "scale": [36, 30, 16] },
        "params": { "hinge": -6, "thickness": 5, "radius": 3, "angle": 160 } })";
    const Scene s = withOperators("[" + flap + R"(, { "type": "retractor",
        "placement": { "translate": [100000, 0, 0], "scale": [10, 10, 10] } }])");
    const Volume out = operators::resampleDeformed(operators::centred(v), s.operators, 0.0f).volume;
    EXPECT_EQ(out.dims.x, v.dims.x);
    EXPECT_EQ(out.dims.y, v.dims.y);
    const Volume flapOnly =
        operators::resampleDeformed(operators::centred(v),
                                    withOperators("[" + flap + "]").operators, 0.0f)
            .volume;
    EXPECT_EQ(out.dims, flapOnly.dims);
    EXPECT_GT(out.dims.z, v.dims.z) << "the flap still grows it";
    EXPECT_EQ(out.data, flapOnly.data) << "and the stray operator changes nothing";
}

TEST_F(CliTest, ExportWritesANrrdOfTheFrameInTheScansType) {
    const auto scene = write("s.json", R"({ "version": 1,
        "volume": { "phantom": "head", "size": [24, 24, 24] },
        "operators": [ { "type": "dilator", "placement": { "scale": [20, 20, 20] },
                         "params": { "radius": 3, "magnification": 2 } } ] })");
    // The extension in any case, as volumes are read.
    CommandResult r = runCutaway("export " + scene.string() + " -o " + (m_dir / "d.NRRD").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const Volume out = readVolume(m_dir / "d.NRRD");
    EXPECT_EQ(out.dims, glm::ivec3(24));
    EXPECT_EQ(out.type, VoxelType::U8) << "the phantom's type: the values, rounded, fit it";
    r = runCutaway("export " + scene.string() + " --type float32 -o " +
                   (m_dir / "f.nrrd").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readVolume(m_dir / "f.nrrd").type, VoxelType::F32);
    EXPECT_EQ(runCutaway("export " + scene.string() + " -o " + (m_dir / "d.png").string()).code, 2);
    const auto overlap = write("o.json", R"({ "version": 1, "volume": { "phantom": "head" },
        "operators": [ { "type": "dilator", "placement": { "scale": [20, 20, 20] } },
                       { "type": "pliers", "placement": { "translate": [5, 0, 0], "scale": [20, 20, 20] } } ] })");
    CommandResult o =
        runCutaway("export " + overlap.string() + " -o " + (m_dir / "o.nrrd").string());
    EXPECT_EQ(o.code, 2) << o.output;
    EXPECT_NE(o.output.find(overlap.string() + " (frame 0): /operators/0 and /operators/1"),
              std::string::npos)
        << o.output;
    EXPECT_NE(o.output.find("overlap"), std::string::npos) << o.output;
    EXPECT_FALSE(std::filesystem::exists(m_dir / "o.nrrd"));
    // An operator outside the volume is warned of, as render does.
    const auto stray = write("stray.json", R"({ "version": 1,
        "volume": { "phantom": "head", "size": [24, 24, 24] },
        "operators": [ { "type": "retractor", "name": "far", "placement": { "translate": [900, 0, 0], "scale": [10, 10, 10] } } ] })");
    CommandResult w = runCutaway("export " + stray.string() + " -o " + (m_dir / "w.nrrd").string());
    EXPECT_EQ(w.code, 0) << w.output;
    EXPECT_NE(w.output.find("warning: " + stray.string() + ": /operators/0: \"far\" lies outside"),
              std::string::npos)
        << w.output;
    EXPECT_EQ(readVolume(m_dir / "w.nrrd").dims, glm::ivec3(24));
}

// --labels-output writes the label volume deformed alike, in its own type,
// on the scan's export grid (even where the label file's origin differs from
// the scan's: the render ignores origins, so the files must overlay); bad
// uses are refused before anything is written.
TEST_F(CliTest, ExportWritesTheLabelsDeformedAlike) {
    Phantom head = makePhantom("head", glm::ivec3(24));
    head.values.origin = glm::dvec3(10.0, -20.0, 5.0);
    writeNrrd(m_dir / "scan.nrrd", head.values);
    writeNrrd(m_dir / "labels.nrrd", head.labels); // origin 0
    const std::string op = R"(
        "operators": [ { "type": "peeler", "placement": { "translate": [0, 0, 8], "scale": [16, 16, 8] },
                         "params": { "angle": 120 } } ] })";
    const auto labelled = write("l.json", R"({ "version": 1, "volume": { "file": "scan.nrrd" },
        "labels": { "file": "labels.nrrd" },)" +
                                              op);
    const std::string v = (m_dir / "v.nrrd").string(), l = (m_dir / "l.nrrd").string();
    CommandResult r =
        runCutaway("export " + labelled.string() + " -o " + v + " --labels-output " + l);
    ASSERT_EQ(r.code, 0) << r.output;
    const Volume values = readVolume(v);
    const Volume labels = readVolume(l);
    EXPECT_EQ(labels.dims, values.dims);
    EXPECT_GT(labels.dims.z, 24) << "the lifted flap grows the grid";
    EXPECT_EQ(labels.origin, values.origin);
    EXPECT_EQ(labels.type, VoxelType::U8);
    std::array<int, 256> count{};
    for (std::size_t i = 0; i < labels.voxelCount(); ++i)
        ++count[std::size_t(labels.raw(i))];
    for (int id = 0; id < 4; ++id)
        EXPECT_GT(count[std::size_t(id)], 0) << "label " << id;
    EXPECT_EQ(count[0] + count[1] + count[2] + count[3], int(labels.voxelCount()))
        << "only the phantom's ids";

    // The same file twice, and a scene without labels: refused, nothing written.
    const std::string same = (m_dir / "same.nrrd").string();
    CommandResult twice =
        runCutaway("export " + labelled.string() + " -o " + same + " --labels-output " + same);
    EXPECT_EQ(twice.code, 2) << twice.output;
    EXPECT_NE(twice.output.find("the same file as -o"), std::string::npos) << twice.output;
    EXPECT_FALSE(std::filesystem::exists(same));
    const auto bare = write("b.json", R"({ "version": 1, "volume": { "file": "scan.nrrd" },)" + op);
    CommandResult b = runCutaway("export " + bare.string() + " -o " + (m_dir / "bv.nrrd").string() +
                                 " --labels-output " + (m_dir / "bl.nrrd").string());
    EXPECT_EQ(b.code, 2) << b.output;
    EXPECT_NE(b.output.find("--labels-output"), std::string::npos) << b.output;
    EXPECT_NE(b.output.find("has no /labels"), std::string::npos) << b.output;
    EXPECT_FALSE(std::filesystem::exists(m_dir / "bv.nrrd"));
    EXPECT_FALSE(std::filesystem::exists(m_dir / "bl.nrrd"));
}

// Without operators, the export of an obliquely oriented scan is the scan:
// every voxel centre at the same physical point, with the same value.
TEST_F(CliTest, ExportWithoutOperatorsKeepsTheScanGeometry) {
    const Phantom orange = orientedOrange();
    writeNrrd(m_dir / "scan.nrrd", orange.values);
    const Scene scene =
        parseScene(nlohmann::json::parse(R"({"version": 1, "volume": {"file": "scan.nrrd"}})"),
                   m_dir, "export test");
    const Volume out = job::exportVolume(scene).volume;
    EXPECT_EQ(out.dims, orange.values.dims);
    EXPECT_EQ(out.space, Space::LPS);
    EXPECT_EQ(expectScanVoxelsInPlace(orange.values, out, 0), glm::ivec3(0));

    // Through the command and the file it writes.
    const auto file = write("s.json", R"({"version": 1, "volume": {"file": "scan.nrrd"}})");
    CommandResult r = runCutaway("export " + file.string() + " -o " + (m_dir / "o.nrrd").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const Volume written = readVolume(m_dir / "o.nrrd");
    EXPECT_EQ(written.dims, orange.values.dims);
    EXPECT_EQ(expectScanVoxelsInPlace(orange.values, written, 0), glm::ivec3(0));
}

// With the grid grown at its low end, the export's origin is the scan's moved
// along the scan's directions (not along the space's axes): every voxel of
// the scan is still a voxel of the export at the same physical point, and
// away from the peeler (the scan's upper half) keeps its value. The labels
// (a file with no orientation of its own) get the same geometry.
TEST_F(CliTest, ExportOfAGrownGridKeepsTheScanGeometry) {
    const Phantom orange = orientedOrange();
    writeNrrd(m_dir / "scan.nrrd", orange.values);
    writeNrrd(m_dir / "labels.nrrd", orange.labels); // no origin, no directions
    const std::string text = std::string(R"({"version": 1, "volume": {"file": "scan.nrrd"},
        "labels": {"file": "labels.nrrd"}, "operators": )") +
                             kGrowingPeeler + "}";
    const Scene scene = parseScene(nlohmann::json::parse(text), m_dir, "export test");
    const job::Exported exported = job::exportVolume(scene, true);
    const Volume& out = exported.volume;
    EXPECT_GT(out.dims.x, orange.values.dims.x);
    EXPECT_GT(out.dims.z, orange.values.dims.z);
    // Slices from 22 on lie above world z = 1.6 mm, clear of the peeler's box
    // (z in [-16, 0]) and of its flap (below the scan).
    const glm::ivec3 shift = expectScanVoxelsInPlace(orange.values, out, 22);
    EXPECT_GT(shift.x, 0) << "the grid grew at -i";
    EXPECT_GT(shift.z, 0) << "the grid grew at -k";
    EXPECT_EQ(shift.y, 0);
    ASSERT_TRUE(exported.labels);
    const Volume& labels = *exported.labels;
    EXPECT_EQ(labels.dims, out.dims);
    EXPECT_EQ(labels.space, Space::LPS);
    EXPECT_EQ(labels.origin, out.origin);
    EXPECT_EQ(labels.direction, out.direction);
    EXPECT_EQ(labels.spacing, out.spacing);

    // The files `cutaway export` writes, read back.
    const auto file = write("g.json", text);
    const std::string v = (m_dir / "v.nrrd").string(), l = (m_dir / "l.nrrd").string();
    CommandResult r = runCutaway("export " + file.string() + " -o " + v + " --labels-output " + l);
    ASSERT_EQ(r.code, 0) << r.output;
    const Volume writtenValues = readVolume(v);
    const Volume writtenLabels = readVolume(l);
    EXPECT_EQ(expectScanVoxelsInPlace(orange.values, writtenValues, 22), shift);
    EXPECT_EQ(writtenLabels.space, Space::LPS);
    EXPECT_EQ(writtenLabels.origin, writtenValues.origin);
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            EXPECT_NEAR(writtenLabels.direction[a][b], obliqueDirections()[a][b], 1e-12);
}

// --oversample K: the same box on a grid K times finer along each axis, in
// the scan's space and directions; the labels alike. Control: K = 1 is the
// grid above. Out of range, the option is refused by name, nothing written.
TEST_F(CliTest, ExportOversampledCoversTheSameBoxKTimesFiner) {
    const Phantom orange = orientedOrange();
    writeNrrd(m_dir / "scan.nrrd", orange.values);
    writeNrrd(m_dir / "labels.nrrd", orange.labels);
    const std::string text = std::string(R"({"version": 1, "volume": {"file": "scan.nrrd"},
        "labels": {"file": "labels.nrrd"}, "operators": )") +
                             kGrowingPeeler + "}";
    const Scene scene = parseScene(nlohmann::json::parse(text), m_dir, "export test");
    const job::Exported one = job::exportVolume(scene, true, 1);
    const job::Exported three = job::exportVolume(scene, true, 3);
    EXPECT_EQ(three.volume.dims, one.volume.dims * 3);
    ASSERT_TRUE(three.labels);
    EXPECT_EQ(three.labels->dims, three.volume.dims);
    EXPECT_EQ(three.volume.direction, one.volume.direction);
    EXPECT_EQ(three.volume.space, one.volume.space);
    // The box's corner, half a voxel before the centre of voxel 0.
    const auto corner = [](const Volume& v) { return v.origin - v.direction * (0.5 * v.spacing); };
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(three.volume.spacing[a], one.volume.spacing[a] / 3.0, 1e-12) << a;
        EXPECT_NEAR(corner(three.volume)[a], corner(one.volume)[a], 1e-9) << a;
        EXPECT_NEAR(three.labels->origin[a], three.volume.origin[a], 1e-12) << a;
    }
    // The fine voxel at the centre of a coarse one's box lies where it does,
    // away from the peeler: the middle of 3 x 3 x 3 takes the coarse value.
    const glm::ivec3 v(20, 20, 30);
    EXPECT_NEAR(three.volume.value(3 * v.x + 1, 3 * v.y + 1, 3 * v.z + 1),
                one.volume.value(v.x, v.y, v.z), 1e-4);

    const auto file = write("o.json", text);
    const std::string out = (m_dir / "o.nrrd").string();
    CommandResult r = runCutaway("export " + file.string() + " -o " + out + " --oversample 2");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readVolume(out).dims, one.volume.dims * 2);
    const std::string refused = (m_dir / "refused.nrrd").string();
    r = runCutaway("export " + file.string() + " -o " + refused + " --oversample 5");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--oversample"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(refused));
}

// An aligned operator's segment with no voxel is bad input, as in a render:
// the export names the operator, exits 2 and writes nothing.
TEST_F(CliTest, ExportRefusesAnAlignedOperatorWithAnEmptySegment) {
    const auto scene = write("e.json", R"({ "version": 1,
        "volume": { "phantom": "head", "size": [24, 24, 24] },
        "operators": [
          { "type": "peeler", "name": "scalp flap", "placement": { "translate": [0, 0, 8], "scale": [16, 16, 8] },
            "alignment": { "mode": "segment", "range": [300, 400] } } ] })");
    CommandResult r = runCutaway("export " + scene.string() + " -o " + (m_dir / "e.nrrd").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(scene.string() + " (frame 0): /operators/0/alignment: scalp flap: the "
                                             "segment of its alignment is empty"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(m_dir / "e.nrrd"));
    // A render refuses it alike, naming the file and the operator's place.
    const auto second = write("e2.json", R"({ "version": 1,
        "volume": { "phantom": "head", "size": [24, 24, 24] }, "render": { "size": [16, 16] },
        "operators": [
          { "type": "dilator", "placement": { "translate": [0, 0, -8], "scale": [8, 8, 6] } },
          { "type": "peeler", "name": "flap", "placement": { "translate": [0, 0, 8], "scale": [16, 16, 6] },
            "alignment": { "mode": "segment", "range": [300, 400] } } ] })");
    CommandResult f = runCutaway("render " + second.string() + " -o " + (m_dir / "e.exr").string());
    EXPECT_EQ(f.code, 2) << f.output;
    EXPECT_NE(f.output.find(second.string() + ": /operators/1/alignment: flap: the segment"),
              std::string::npos)
        << f.output;
    EXPECT_FALSE(std::filesystem::exists(m_dir / "e.exr"));
}

} // namespace cutaway::test

namespace cutaway::test {

// Sequential composition: an identity operator applied after a retractor, in
// an overlapping box, leaves the retractor's result unchanged.
TEST(DeformedVolume, SequentialCompositionAppliesOperatorsInOrder) {
    const Volume v = makePhantom("head", {40, 40, 40}).values;
    const Scene s = withOperators(R"([
        { "type": "retractor", "placement": { "translate": [0, 0, 10], "scale": [26, 34, 20] },
          "params": { "opening": 10 } },
        { "type": "dilator", "placement": { "translate": [4, 0, 8], "scale": [20, 20, 20] },
          "params": { "magnification": 1 } }])");
    const auto once = operators::resampleDeformed(operators::centred(v), {s.operators[0]}, -1.0f);
    const auto both = operators::resampleSequentially(operators::centred(v), s.operators, -1.0f);
    ASSERT_EQ(both.volume.dims, once.volume.dims);
    EXPECT_EQ(both.worldLo, once.worldLo);
    for (std::size_t i = 0; i < once.volume.voxelCount(); ++i)
        ASSERT_NEAR(both.volume.value(i), once.volume.value(i), 1e-3) << i;

    // A real second operator changes what the first left: pliers pull at it.
    const Scene pull = withOperators(R"([
        { "type": "retractor", "placement": { "translate": [0, 0, 10], "scale": [26, 34, 20] },
          "params": { "opening": 10 } },
        { "type": "pliers", "placement": { "translate": [4, 0, 8], "scale": [20, 20, 20] },
          "params": { "radius": 8, "displacement": [0, 0, 3] } }])");
    const auto pulled =
        operators::resampleSequentially(operators::centred(v), pull.operators, -1.0f);
    double changed = 0.0;
    for (std::size_t i = 0; i < once.volume.voxelCount(); ++i)
        changed = std::max(changed, std::abs(pulled.volume.value(i) - once.volume.value(i)));
    EXPECT_GT(changed, 10.0);
}

} // namespace cutaway::test
