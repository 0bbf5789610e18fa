// `cutaway export` with feature-aligned operators (paper Eq. 3, 4): the
// feature stays where it is, the rest moves as without alignment or is cut.
// Checked per voxel against the same scene with its operator axis-aligned.
#include "job/export_volume.hpp"
#include "scene/scene.hpp"
#include "volume/phantom.hpp"

#include <array>
#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

using nlohmann::json;

constexpr int kSize = 48;

// The head phantom (skin, skull, brain; 1 mm voxels) and a peeler over its
// crown whose flap reaches through the skull into the brain.
json peelerScene(const json& alignment) {
    return {
        {"version", 1},
        {"volume", {{"phantom", "head"}, {"size", {kSize, kSize, kSize}}}},
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
    e.input = makePhantom("head", glm::ivec3(kSize)).values;
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

void expectFeatureKept(const Counts& c) {
    EXPECT_GT(c.featureMoved, 200) << "control: the operator without alignment moves the feature";
    EXPECT_EQ(c.keptInPlace, c.feature) << "every feature voxel keeps its value";
    EXPECT_GT(c.otherMoved, 200) << "the rest moves with the operator";
    EXPECT_EQ(c.otherWrong, 0) << "the rest moves as without alignment, or is cut";
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
    expectFeatureKept(classify(e, [&](int x, int y, int z) {
        const double v = e.input.value(x, y, z);
        return v >= 180 && v <= 255 ? Kind::Feature : Kind::Other;
    }));
    // Nor is the skull also carried along: a moved point whose pre-image p0
    // is the feature is empty (Eq. 4). Without alignment the flap carries
    // the skull's values up (about 1000 voxels more of them than the scan
    // has); with it only moved points whose trilinear sample leans on skull
    // voxels add to them (about 150). Ignoring M at p0 adds about 2000.
    const auto bright = [](const Volume& v) {
        int n = 0;
        for (std::size_t i = 0; i < v.voxelCount(); ++i)
            n += v.value(i) >= 180 ? 1 : 0;
        return n;
    };
    const int carried = bright(e.axis) - bright(e.input);
    EXPECT_GT(carried, 300) << "control: the flap carries the skull without alignment";
    EXPECT_LT(bright(e.aligned) - bright(e.input), 0.3 * carried);
}

// Segment alignment by labels: the brain's voxels stay.
TEST(ExportAlignment, SegmentByLabelsKeepsTheLabelledVoxels) {
    const Volume labels = makePhantom("head", glm::ivec3(kSize)).labels;
    const Exports e = exportBoth({{"mode", "segment"}, {"labels", {"brain"}}, {"band", 1}});
    expectFeatureKept(classify(e, [&](int x, int y, int z) {
        return labels.value(x, y, z) == 3.0 ? Kind::Feature : Kind::Other;
    }));
}

} // namespace cutaway::test

namespace cutaway::test {

// The labels go where their voxels go: a voxel well inside one label in the
// exported label volume has a value of that tissue in the exported scan,
// whether the flap carries everything (axis-aligned) or leaves the brain in
// place (segment-aligned by its label).
TEST(ExportLabels, LabelsMoveWithTheirVoxels) {
    // Each tissue's values, over the scan's voxels inside it (all six
    // neighbours of the same label: no partial volume).
    const Phantom phantom = makePhantom("head", glm::ivec3(kSize));
    const auto interior = [](const Volume& l, int x, int y, int z) {
        const double id = l.value(x, y, z);
        for (const glm::ivec3 d :
             {glm::ivec3(1, 0, 0), glm::ivec3(-1, 0, 0), glm::ivec3(0, 1, 0), glm::ivec3(0, -1, 0),
              glm::ivec3(0, 0, 1), glm::ivec3(0, 0, -1)}) {
            const glm::ivec3 q = glm::ivec3(x, y, z) + d;
            if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
                glm::any(glm::greaterThanEqual(q, l.dims)) || l.value(q.x, q.y, q.z) != id)
                return false;
        }
        return true;
    };
    std::array<double, 4> lo{1e9, 1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9, -1e9};
    for (int z = 0; z < kSize; ++z)
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                if (!interior(phantom.labels, x, y, z)) continue;
                const auto id = std::size_t(phantom.labels.value(x, y, z));
                lo[id] = std::min(lo[id], phantom.values.value(x, y, z));
                hi[id] = std::max(hi[id], phantom.values.value(x, y, z));
            }

    for (const json& alignment :
         {json{{"mode", "axis"}}, json{{"mode", "segment"}, {"labels", {"brain"}}}}) {
        const job::Exported e = job::exportVolume(parse(peelerScene(alignment)), true);
        ASSERT_TRUE(e.labels);
        const Volume& labels = *e.labels;
        ASSERT_EQ(labels.dims, e.volume.dims);
        EXPECT_EQ(labels.type, VoxelType::U8) << "the label volume's own type";
        EXPECT_EQ(labels.origin, e.volume.origin);
        const glm::ivec3 offset = glm::ivec3(
            glm::round((phantom.values.origin - labels.origin) / phantom.values.spacing));
        // A voxel inside one label whose value is off that tissue's range (by
        // more than a tenth of it: the scan's trilinear sample at a moved
        // point leans on its neighbours) counts against the export.
        int inside = 0, off = 0, moved = 0;
        for (int z = 0; z < labels.dims.z; ++z)
            for (int y = 0; y < labels.dims.y; ++y)
                for (int x = 0; x < labels.dims.x; ++x) {
                    if (!interior(labels, x, y, z)) continue;
                    const auto id = std::size_t(labels.value(x, y, z));
                    if (id == 0) continue;
                    ++inside;
                    const double v = e.volume.value(x, y, z), margin = 0.1 * (hi[id] - lo[id]);
                    if (v < lo[id] - margin || v > hi[id] + margin) ++off;
                    const glm::ivec3 q = glm::ivec3(x, y, z) - offset;
                    const bool inScan = glm::all(glm::greaterThanEqual(q, glm::ivec3(0))) &&
                                        glm::all(glm::lessThan(q, glm::ivec3(kSize)));
                    if (!inScan || phantom.labels.value(q.x, q.y, q.z) != double(id)) ++moved;
                }
        // Axis-aligned: 15525 voxels moved, 37 of 31621 off; the brain kept:
        // 36 of 17462 off. Labels resampled without the brain's mask (so
        // carried off with the flap while its values stay): 15433 off.
        if (alignment["mode"] == "axis") {
            EXPECT_GT(moved, 500) << "control: the flap carries labelled voxels elsewhere";
        }
        EXPECT_LT(off, inside / 100)
            << alignment.dump() << ": " << off << " of " << inside << " voxels off their tissue";
    }
}

} // namespace cutaway::test
