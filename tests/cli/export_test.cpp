// `cutaway export`: the deformed volume resampled for other tools.
#include "cli_util.hpp"
#include "job/export_volume.hpp"
#include "operators/deformed_volume.hpp"
#include "scene/scene.hpp"
#include "volume/phantom.hpp"

#include <array>
#include <filesystem>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

Scene withOperators(const std::string& operators) {
    return parseScene(nlohmann::json::parse(R"({"version": 1, "volume": {"phantom": "head"},
        "operators": )" + operators + "}"),
                      "/nonexistent", "export test");
}

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

TEST_F(CliTest, ExportWritesAFloatNrrdOfTheFrame) {
    const auto scene = write("s.json", R"({ "version": 1,
        "volume": { "phantom": "head", "size": [24, 24, 24] },
        "operators": [ { "type": "dilator", "placement": { "scale": [20, 20, 20] },
                         "params": { "radius": 3, "magnification": 2 } } ] })");
    CommandResult r = runCutaway("export " + scene.string() + " -o " + (m_dir / "d.nrrd").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const Volume out = readVolume(m_dir / "d.nrrd");
    EXPECT_EQ(out.dims, glm::ivec3(24));
    EXPECT_EQ(out.type, VoxelType::F32);
    EXPECT_EQ(runCutaway("export " + scene.string() + " -o " + (m_dir / "d.png").string()).code, 2);
    const auto overlap = write("o.json", R"({ "version": 1, "volume": { "phantom": "head" },
        "operators": [ { "type": "dilator", "placement": { "scale": [20, 20, 20] } },
                       { "type": "pliers", "placement": { "translate": [5, 0, 0], "scale": [20, 20, 20] } } ] })");
    CommandResult o =
        runCutaway("export " + overlap.string() + " -o " + (m_dir / "o.nrrd").string());
    EXPECT_EQ(o.code, 2) << o.output;
    EXPECT_NE(o.output.find("overlap"), std::string::npos) << o.output;
    EXPECT_FALSE(std::filesystem::exists(m_dir / "o.nrrd"));
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
    EXPECT_NE(r.output.find("scalp flap: the segment of its alignment is empty"), std::string::npos)
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(m_dir / "e.nrrd"));
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
