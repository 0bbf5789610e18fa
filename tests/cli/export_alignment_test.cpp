// `cutaway export` with feature-aligned operators (paper Eq. 3, 4): the
// feature stays where it is, the rest moves as without alignment or is cut.
// Checked per voxel against the same scene with its operator axis-aligned.
#include "job/export_volume.hpp"
#include "job/render_job.hpp"
#include "operators/deformed_volume.hpp"
#include "scene/scene.hpp"
#include "volume/phantom.hpp"
#include "volume/tilted_bone.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

using nlohmann::json;

constexpr int kSize = 48;
// Voxels of different sizes along each axis, so that millimetres and voxels
// cannot be mixed up unseen.
const glm::dvec3 kSpacing(1.0, 1.25, 0.8);

// The head phantom (skin, skull, brain) as the scenes below load it.
Phantom phantom() {
    Phantom p = makePhantom("head", glm::ivec3(kSize));
    p.values.spacing = kSpacing; // as /volume/spacing does
    p.labels.spacing = kSpacing;
    return p;
}

// The head phantom and a peeler over its crown whose flap reaches through
// the skull into the brain.
json peelerScene(const json& alignment) {
    return {
        {"version", 1},
        {"volume",
         {{"phantom", "head"},
          {"size", {kSize, kSize, kSize}},
          {"spacing", {kSpacing.x, kSpacing.y, kSpacing.z}}}},
        {"labels", {{"phantom", true}}},
        {"operators",
         {{{"type", "peeler"},
           {"placement", {{"translate", {0, 0, 12}}, {"scale", {40, 40, 24}}}},
           {"alignment", alignment},
           {"params", {{"hinge", -8}, {"thickness", 20}, {"radius", 3}, {"angle", 130}}}}}},
    };
}

Scene parse(const json& document) {
    return parseScene(document, "/nonexistent", "export alignment test");
}

// The export of `alignment` and of the same operator axis-aligned, on the
// input's grid: voxel i of the scan is voxel at(i) of both outputs.
struct Exports {
    Volume input;
    Volume aligned;
    Volume axis;
    glm::ivec3 offset{0}; // the input's voxel (0,0,0) in the outputs' grid
    float empty = 0.0f;

    double alignedAt(int x, int y, int z) const {
        return aligned.value(x + offset.x, y + offset.y, z + offset.z);
    }
    double axisAt(int x, int y, int z) const {
        return axis.value(x + offset.x, y + offset.y, z + offset.z);
    }
};

Exports exportBoth(const json& alignment) {
    Exports e;
    e.input = phantom().values;
    e.aligned = job::exportVolume(parse(peelerScene(alignment))).volume;
    e.axis = job::exportVolume(parse(peelerScene({{"mode", "axis"}}))).volume;
    EXPECT_EQ(e.aligned.dims, e.axis.dims);
    EXPECT_EQ(e.aligned.origin, e.axis.origin);
    e.offset = glm::ivec3(glm::round((e.input.origin - e.aligned.origin) / e.input.spacing));
    e.empty = static_cast<float>(valueRange(e.input).min);
    return e;
}

struct Counts {
    int feature = 0;      // voxels of the feature
    int featureMoved = 0; // ... that the axis-aligned operator moves or cuts
    int keptInPlace = 0;  // ... that keep their value with alignment
    int other = 0;        // voxels outside the feature
    int otherMoved = 0;   // ... that move with alignment as without it
    int otherWrong = 0;   // ... that neither move as without it nor are empty
};

enum class Kind { Feature, Other, Either };

// Eq. 4 at each voxel centre p' of the scan: a feature voxel (M(p') >= 0.5)
// takes the case "masked", its own value; any other voxel takes p0 (what the
// axis-aligned operator gives there) or nothing. `Either`: too close to
// M = 0.5 to tell, not counted.
Counts classify(const Exports& e, const std::function<Kind(int, int, int)>& kind) {
    Counts c;
    for (int z = 0; z < kSize; ++z)
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const double in = e.input.value(x, y, z);
                const double aligned = e.alignedAt(x, y, z), axis = e.axisAt(x, y, z);
                const Kind k = kind(x, y, z);
                if (k == Kind::Either) continue;
                if (k == Kind::Feature) {
                    ++c.feature;
                    if (std::abs(axis - in) > 1e-3) ++c.featureMoved;
                    if (std::abs(aligned - in) <= 1e-3) ++c.keptInPlace;
                } else {
                    ++c.other;
                    if (std::abs(aligned - axis) <= 1e-3 && std::abs(axis - in) > 1e-3)
                        ++c.otherMoved;
                    else if (std::abs(aligned - axis) > 1e-3 && aligned != e.empty)
                        ++c.otherWrong;
                }
            }
    return c;
}

// `refilled`: how many voxels of the rest may differ from the axis-aligned
// export (segment alignment: a moved point whose trilinear sample leans on
// the segment's voxels reads them without the segment's values, see
// operators/moved_value.hpp).
void expectFeatureKept(const Counts& c, int refilled = 0) {
    EXPECT_GT(c.featureMoved, 200) << "control: the operator without alignment moves the feature";
    EXPECT_EQ(c.keptInPlace, c.feature) << "every feature voxel keeps its value";
    EXPECT_GT(c.otherMoved, 200) << "the rest moves with the operator";
    EXPECT_LE(c.otherWrong, refilled) << "the rest moves as without alignment, or is cut";
}

} // namespace

// Surface alignment: what lies deeper than `depth` below the surface (M >= 0.5
// where the distance field DT >= depth) stays; the scalp above it is peeled.
TEST(ExportAlignment, SurfaceKeepsWhatLiesBelowItsDepth) {
    const json alignment = {{"mode", "surface"}, {"depth", 3}, {"band", 1}};
    const Exports e = exportBoth(alignment);
    const Scene scene = parse(peelerScene(alignment));
    const std::vector<float> dt = job::featureFieldCpu(e.input, nullptr, scene.operators[0]);
    ASSERT_EQ(dt.size(), e.input.voxelCount());
    expectFeatureKept(classify(e, [&](int x, int y, int z) {
        const float d = dt[e.input.index(x, y, z)];
        return d >= 3.01f ? Kind::Feature : d <= 2.99f ? Kind::Other : Kind::Either;
    }));
}

// Segment alignment by a value range (the skull's bright values): the skull
// stays, skin and brain in the box move.
TEST(ExportAlignment, SegmentByRangeKeepsTheValuesInTheRange) {
    const Exports e = exportBoth({{"mode", "segment"}, {"range", {180, 255}}, {"band", 1}});
    const Counts c = classify(e, [&](int x, int y, int z) {
        const double v = e.input.value(x, y, z);
        return v >= 180 && v <= 255 ? Kind::Feature : Kind::Other;
    });
    expectFeatureKept(c, c.otherMoved / 5);
    // Nor is the skull also carried along: a moved point whose pre-image p0
    // is the feature is empty (Eq. 4), and one whose trilinear sample leans
    // on skull voxels reads them without the skull's values. So the skull's
    // values are where the scan has them and nowhere else. Without alignment
    // the flap carries them up (229 voxels more than the scan has; about 1000
    // when the peeler folded in its box's units, 1.7x too thick); ignoring M
    // at p0 added about 2000, sampling the scan's own values at moved points
    // about 150 (with that thicker flap).
    const auto bright = [](const Volume& v) {
        int n = 0;
        for (std::size_t i = 0; i < v.voxelCount(); ++i)
            n += v.value(i) >= 180 ? 1 : 0;
        return n;
    };
    const int carried = bright(e.axis) - bright(e.input);
    EXPECT_GT(carried, 150) << "control: the flap carries the skull without alignment";
    EXPECT_EQ(bright(e.aligned), bright(e.input));
}

// Material leaves a segment-aligned operator's segment where the smoothed
// segment lets it go, as the render decides (tests/gpu/segment_edge_test.cpp):
// a flap stood upright off bone whose top is tilted across the grid is as
// thick as the tissue over the plane, a smooth ramp. Measured as the count of
// non-empty voxels through the flap (1 mm voxels, oversampled 4 times: 0.25 mm
// steps, 0.07 mm RMS by themselves), its residual about a fitted quadratic:
// 0.105 mm; keeping every voxel of the segment, as where labels classify, the
// underside is the voxels' staircase: 0.207 mm. Bounds 0.15 mm, and the
// control 1.6 times rougher.
TEST(ExportAlignment, MaterialLeavesASegmentAlongItsSmoothSurface) {
    const Volume volume = tissueOverTiltedBone(64, 1.0);
    const Scene scene = parse({{"version", 1},
                               {"volume", {{"phantom", "head"}, {"size", {8, 8, 8}}}},
                               {"operators", {standingFlapPeeler()}}});
    const operators::FeatureFieldMaker fieldFor = [](const Volume& v, const OperatorSpec& op) {
        return std::make_shared<const std::vector<float>>(job::featureFieldCpu(v, nullptr, op));
    };
    const auto roughness = [&](bool keepSegmentVoxels) {
        const operators::Resampling how{operators::Sampling::Trilinear, keepSegmentVoxels, 4};
        const operators::PlacedVolume out = operators::resampleDeformed(
            operators::centred(volume), scene.operators, 0.0f, fieldFor, how);
        const Volume& v = out.volume;
        std::vector<FitSample> samples;
        for (int z = 0; z < v.dims.z; ++z)
            for (int y = 0; y < v.dims.y; ++y) {
                const glm::dvec3 at = out.worldLo + (glm::dvec3(0, y, z) + 0.5) * v.spacing;
                if (at.z < 12.5 || at.z > 40.0 || std::abs(at.y) > 18.0) continue;
                int through = 0;
                for (int x = 0; x < v.dims.x; ++x)
                    through += v.value(x, y, z) > 25.0 ? 1 : 0;
                samples.push_back({at.y, at.z, through * v.spacing.x});
            }
        EXPECT_GT(samples.size(), 3000u);
        return quadraticResidualRms(samples);
    };
    const double smooth = roughness(false), stepped = roughness(true);
    std::printf("flap thickness residual %.3f mm, keeping the segment's voxels %.3f mm\n", smooth,
                stepped);
    EXPECT_LT(smooth, 0.15);
    EXPECT_GT(stepped, 1.6 * smooth);
}

// Segment alignment by labels: the brain's voxels stay.
TEST(ExportAlignment, SegmentByLabelsKeepsTheLabelledVoxels) {
    const Volume labels = phantom().labels;
    const Exports e = exportBoth({{"mode", "segment"}, {"labels", {"brain"}}, {"band", 1}});
    const Counts c = classify(e, [&](int x, int y, int z) {
        return labels.value(x, y, z) == 3.0 ? Kind::Feature : Kind::Other;
    });
    expectFeatureKept(c, c.otherMoved / 5);
}

} // namespace cutaway::test

namespace cutaway::test {

namespace {

// Whether a voxel and its six neighbours have the same label.
bool interior(const Volume& labels, int x, int y, int z) {
    const double id = labels.value(x, y, z);
    for (const glm::ivec3 d : {glm::ivec3(1, 0, 0), glm::ivec3(-1, 0, 0), glm::ivec3(0, 1, 0),
                               glm::ivec3(0, -1, 0), glm::ivec3(0, 0, 1), glm::ivec3(0, 0, -1)}) {
        const glm::ivec3 q = glm::ivec3(x, y, z) + d;
        if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
            glm::any(glm::greaterThanEqual(q, labels.dims)) || labels.value(q.x, q.y, q.z) != id)
            return false;
    }
    return true;
}

struct LabelCheck {
    int inside = 0; // exported voxels inside a tissue's label
    int off = 0;    // ... whose exported value is not that tissue's
    int moved = 0;  // ... whose label is not the scan's at the same place
};

// Each exported voxel inside one label (not the background) against the range
// of that tissue's values over the scan's voxels inside it (no partial
// volume); a value off it by more than a tenth of the range (a moved point's
// trilinear sample leans on its neighbours) counts as off.
LabelCheck checkLabels(const job::Exported& e) {
    const Phantom head = phantom();
    std::array<double, 4> lo{1e9, 1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9, -1e9};
    for (int z = 0; z < kSize; ++z)
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                if (!interior(head.labels, x, y, z)) continue;
                const auto id = std::size_t(head.labels.value(x, y, z));
                lo[id] = std::min(lo[id], head.values.value(x, y, z));
                hi[id] = std::max(hi[id], head.values.value(x, y, z));
            }
    LabelCheck c;
    EXPECT_TRUE(e.labels);
    if (!e.labels) return c;
    const Volume& labels = *e.labels;
    EXPECT_EQ(labels.dims, e.volume.dims);
    EXPECT_EQ(labels.type, VoxelType::U8) << "the label volume's own type";
    EXPECT_EQ(labels.origin, e.volume.origin);
    EXPECT_EQ(labels.spacing, e.volume.spacing);
    if (labels.dims != e.volume.dims) return c;
    const glm::ivec3 offset =
        glm::ivec3(glm::round((head.values.origin - labels.origin) / head.values.spacing));
    for (int z = 0; z < labels.dims.z; ++z)
        for (int y = 0; y < labels.dims.y; ++y)
            for (int x = 0; x < labels.dims.x; ++x) {
                if (!interior(labels, x, y, z)) continue;
                const auto id = std::size_t(labels.value(x, y, z));
                if (id == 0) continue;
                ++c.inside;
                const double v = e.volume.value(x, y, z), margin = 0.1 * (hi[id] - lo[id]);
                if (v < lo[id] - margin || v > hi[id] + margin) ++c.off;
                const glm::ivec3 q = glm::ivec3(x, y, z) - offset;
                const bool inScan = glm::all(glm::greaterThanEqual(q, glm::ivec3(0))) &&
                                    glm::all(glm::lessThan(q, glm::ivec3(kSize)));
                if (!inScan || head.labels.value(q.x, q.y, q.z) != double(id)) ++c.moved;
            }
    return c;
}

} // namespace

// The labels go where their voxels go: a voxel well inside one label in the
// exported label volume has a value of that tissue in the exported scan,
// whether the flap carries everything (axis-aligned) or leaves the brain in
// place (segment-aligned by its label). Axis-aligned: about 15500 voxels
// moved, 37 of 31600 off; the brain kept: 36 of 17500 off. Labels resampled
// without the brain's mask (carried off with the flap while its values
// stay) gave 15433 off.
TEST(ExportLabels, LabelsMoveWithTheirVoxels) {
    for (const json& alignment :
         {json{{"mode", "axis"}}, json{{"mode", "segment"}, {"labels", {"brain"}}}}) {
        const LabelCheck c = checkLabels(job::exportVolume(parse(peelerScene(alignment)), true));
        if (alignment["mode"] == "axis") {
            EXPECT_GT(c.moved, 500) << "control: the flap carries labelled voxels elsewhere";
        }
        EXPECT_LT(c.off, c.inside / 100)
            << alignment.dump() << ": " << c.off << " of " << c.inside << " voxels off";
    }
}

// Sequential composition: a retractor opens the side of the head, then the
// peeler, segment-aligned by the skull's values in what the retractor left,
// lifts the scalp. The labels follow both steps, and the peeler's mask is
// the one made from the scan's intermediate volume (the labels' own values
// would give it no voxel at all).
TEST(ExportLabels, LabelsFollowSequentialComposition) {
    json scene = peelerScene({{"mode", "segment"}, {"range", {180, 255}}, {"band", 1}});
    scene["render"] = {{"operator_composition", "sequential"}};
    scene["operators"].insert(
        scene["operators"].begin(),
        json{{"type", "retractor"},
             {"placement",
              {{"translate", {20, 0, -6}}, {"rotate", {0, 90, 0}}, {"scale", {16, 30, 16}}}},
             {"params", {{"opening", 8}}}});
    const job::Exported e = job::exportVolume(parse(scene), true);
    const LabelCheck c = checkLabels(e);
    EXPECT_GT(c.moved, 200) << "control: the operators move labelled voxels";
    EXPECT_LT(c.off, c.inside / 100) << c.off << " of " << c.inside << " voxels off";
    // The upper skull, which the retractor does not reach, stays in place as
    // under the peeler alone, while the same peeler axis-aligned lifts it.
    const auto variant = [&](const std::function<void(json&)>& change) {
        json changed = scene;
        change(changed);
        return job::exportVolume(parse(changed), true);
    };
    const job::Exported retractorOnly =
        variant([](json& d) { d["operators"].erase(d["operators"].begin() + 1); });
    const job::Exported axis = variant([](json& d) {
        d["operators"][1]["alignment"] = {{"mode", "axis"}};
    });
    const Phantom head = phantom();
    const auto upperSkullInPlace = [&](const job::Exported& x) {
        const glm::ivec3 offset =
            glm::ivec3(glm::round((head.values.origin - x.volume.origin) / head.values.spacing));
        int n = 0;
        for (int z = kSize / 2; z < kSize; ++z)
            for (int y = 0; y < kSize; ++y)
                for (int v = 0; v < kSize; ++v) {
                    const glm::ivec3 o = glm::ivec3(v, y, z) + offset;
                    if (head.labels.value(v, y, z) == 2.0 && x.labels->value(o.x, o.y, o.z) == 2.0)
                        ++n;
                }
        return n;
    };
    // The retractor leaves all 2690 voxels of the upper skull in place. The
    // peeler keeps 2278 of them, alone or after the retractor (the rest are
    // skull by label but below 180 by value: not its segment); axis-aligned,
    // it keeps 1018 fewer.
    const int before = upperSkullInPlace(retractorOnly);
    const job::Exported peelerOnly =
        variant([](json& d) { d["operators"].erase(d["operators"].begin()); });
    const int kept = upperSkullInPlace(peelerOnly);
    EXPECT_GT(kept, before / 2);
    EXPECT_NEAR(upperSkullInPlace(e), kept, 0.02 * kept);
    EXPECT_LT(upperSkullInPlace(axis), before - 300) << "control: the peeler lifts the skull";
}

} // namespace cutaway::test

namespace cutaway::test {

// The render's sequential pre-pass fills its cuts as the export does: with the
// scan's smallest value where the window starts above it (so a surface
// threshold between the two sees the cuts as background), which normalizes to
// the same texel as the window's bottom.
TEST(ExportLabels, SequentialCutsHoldTheScansSmallestValue) {
    json scene = peelerScene({{"mode", "axis"}});
    scene["volume"]["window"] = {60, 255};
    scene["render"] = {{"operator_composition", "sequential"}};
    scene["operators"].push_back(json{
        {"type", "dilator"}, {"placement", {{"translate", {0, 0, -12}}, {"scale", {8, 8, 8}}}}});
    const Scene s = parse(scene);
    const Volume scan = phantom().values;
    EXPECT_EQ(job::emptyValue(s, scan), 0.0f);
    const job::FrameVolume frame = job::frameVolume(s);
    const auto count = [](const Volume& v, double value) {
        int n = 0;
        for (std::size_t i = 0; i < v.voxelCount(); ++i)
            n += v.value(i) == value ? 1 : 0;
        return n;
    };
    // The peeler's hole and the space its flap lifts into are empty, and
    // hold 0, not 60 (a few voxels still are 60: resampled tissue).
    EXPECT_GT(count(*frame.scan, 0.0), count(scan, 0.0) + 1000);
    EXPECT_LT(count(*frame.scan, 60.0), count(scan, 60.0) + 100) << "cuts at the window's bottom";
}

} // namespace cutaway::test
