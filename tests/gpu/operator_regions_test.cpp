// Empty-space skipping for operator proxies (render/skipping/operator_regions.hpp):
// the regions must cover every point of a deformed box whose sample can be
// visible, so that an image rendered with them equals the image rendered
// with the operator shader over the whole box.
#include "bake/feature_bake.hpp"
#include "bake/feature_ranges.hpp"
#include "bake/gradient_bake.hpp"
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "operators/operator_geometry.hpp"
#include "render/gpu_volume.hpp"
#include "render/skipping/occupancy.hpp"
#include "render/skipping/operator_regions.hpp"
#include "render/skipping/ray_cells.hpp"
#include "render/volume_renderer.hpp"
#include "scene/scene.hpp"
#include "shared/feature.h"
#include "shared/operators.h"
#include "volume/segmentation.hpp"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <utility>

namespace cutaway::test {
namespace {

// One operator of each kind over the head phantom (64^3 voxels of 1 mm),
// placed where each cuts into it.
const char* const kOperators[] = {
    R"({ "type": "peeler", "placement": { "translate": [0, 0, 16], "scale": [50, 50, 30] },
         "params": { "hinge": -10, "thickness": 12, "angle": 130 } })",
    R"({ "type": "retractor", "placement": { "translate": [0, -10, 14], "scale": [30, 40, 30],
         "rotate": [20, 0, 0] }, "params": { "opening": 14 } })",
    R"({ "type": "pliers", "placement": { "translate": [0, 24, 4], "scale": [30, 20, 30] } })",
    R"({ "type": "dilator", "placement": { "translate": [12, 0, 0], "scale": [24, 24, 24] },
         "params": { "magnification": 1.5 } })",
};

Scene sceneWith(const std::string& op, const std::string& alignment, double spacing = 1.0) {
    nlohmann::json doc = operatorPhantomDocument();
    nlohmann::json o = nlohmann::json::parse(op);
    if (!alignment.empty()) o["alignment"] = nlohmann::json::parse(alignment);
    doc["operators"] = nlohmann::json::array({o});
    doc["render"]["slice_spacing"] = spacing;
    return parseScene(doc, "/nonexistent", "test");
}

// The map's value at local q as the GPU samples it: trilinear between texel
// centres, clamped to the edge, of the texels operator_bake.comp writes.
glm::vec4 sampledMap(const OperatorSpec& spec, const operators::LocalBox& domain, glm::dvec3 q) {
    const glm::ivec3 res = spec.resolution;
    const glm::dvec3 t = (q - domain.lo) / (domain.hi - domain.lo) * glm::dvec3(res) - 0.5;
    const glm::ivec3 i0 = glm::ivec3(glm::floor(t));
    const glm::dvec3 f = t - glm::dvec3(i0);
    glm::vec4 sum(0.0f);
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 d((c & 1) ? 1 : 0, (c & 2) ? 1 : 0, (c & 4) ? 1 : 0);
        const glm::ivec3 i = glm::clamp(i0 + d, glm::ivec3(0), res - 1);
        const glm::vec3 centre = glm::mix(glm::vec3(domain.lo), glm::vec3(domain.hi),
                                          (glm::vec3(i) + 0.5f) / glm::vec3(res));
        const glm::vec4 b = shader::operatorBackward(centre, spec.params);
        const double w =
            (d.x ? f.x : 1.0 - f.x) * (d.y ? f.y : 1.0 - f.y) * (d.z ? f.z : 1.0 - f.z);
        sum += float(w) * glm::vec4(glm::vec3(b) - centre, b.w);
    }
    return sum;
}

bool inside(const operators::LocalBox& b, glm::dvec3 q) {
    return glm::all(glm::greaterThanEqual(q, b.lo)) && glm::all(glm::lessThanEqual(q, b.hi));
}

} // namespace

TEST(OperatorRegions, CoverEveryPointWhoseSampleCanShow) {
    const Scene base = sceneWith(kOperators[0], "");
    const Volume volume = job::loadSceneVolume(base);
    const render::Box box{-glm::dvec3(volume.dims) * 0.5, glm::dvec3(volume.dims) * 0.5};
    const bake::ValueWindow window = job::sceneWindow(base, volume);
    const render::BrickOccupancy occupancy = render::brickOccupancy(
        volume, box, window,
        render::VisibleValues({&base.transfer}, window,
                              base.render.classification == Classification::Preintegrated),
        1);
    std::mt19937 rng(7);
    for (const char* op : kOperators) {
        const OperatorSpec spec = sceneWith(op, "").operators.at(0);
        SCOPED_TRACE(spec.name);
        const operators::WorldBox world{spec.localToWorld,
                                        operators::deformedBounds(spec.params, spec.resolution)};
        const std::vector<operators::LocalBox> regions =
            render::operatorRegions(spec, world, occupancy, 1.0);
        // Inside the box, and no two overlap (they would be shaded twice).
        for (std::size_t i = 0; i < regions.size(); ++i) {
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(regions[i].lo, world.local.lo)));
            EXPECT_TRUE(glm::all(glm::lessThanEqual(regions[i].hi, world.local.hi)));
            for (std::size_t j = 0; j < i; ++j) {
                const glm::dvec3 lo = glm::max(regions[i].lo, regions[j].lo);
                const glm::dvec3 hi = glm::min(regions[i].hi, regions[j].hi);
                EXPECT_FALSE(glm::all(glm::lessThan(lo + 1e-9, hi))) << i << " overlaps " << j;
            }
        }
        const glm::dvec3 extent = world.local.hi - world.local.lo;
        if (spec.type == OperatorType::Peeler) { // its flap swings out into the air: split
            EXPECT_LT(render::coverage(regions, world.local), render::kWholeBoxCoverage);
        }
        // Random points p' of the box whose p' or sampled pre-image p0 lies in an
        // occupied brick must be in a region.
        std::uniform_real_distribution<double> u(0.0, 1.0);
        int needed = 0;
        for (int n = 0; n < 20000; ++n) {
            const glm::dvec3 q = world.local.lo + glm::dvec3(u(rng), u(rng), u(rng)) * extent;
            const glm::vec4 m = sampledMap(spec, world.local, q);
            const glm::dvec3 prime(spec.localToWorld * glm::dvec4(q, 1.0));
            const glm::dvec3 p0(spec.localToWorld * glm::dvec4(q + glm::dvec3(glm::vec3(m)), 1.0));
            const bool visible =
                occupancy.anyIn(prime, prime) || (m.w > 0.0f && occupancy.anyIn(p0, p0));
            if (!visible) continue;
            ++needed;
            bool found = false;
            for (const operators::LocalBox& r : regions)
                found = found || inside(r, q);
            ASSERT_TRUE(found) << "q " << q.x << " " << q.y << " " << q.z;
        }
        EXPECT_GT(needed, 1000);
    }
}

TEST(OperatorRegions, FollowTheOccupancy) {
    const OperatorSpec spec = sceneWith(kOperators[1], "").operators.at(0);
    const operators::WorldBox world{spec.localToWorld,
                                    operators::deformedBounds(spec.params, spec.resolution)};
    const render::Box box{glm::dvec3(-32.0), glm::dvec3(32.0)};
    // Everything occupied: the regions fill the whole box.
    const auto all = render::operatorRegions(spec, world, render::fullOccupancy(box), 1.0);
    EXPECT_NEAR(render::coverage(all, world.local), 1.0, 1e-9);
    // Nothing occupied: nothing to shade.
    render::BrickOccupancy none = render::fullOccupancy(box);
    none.flags[0] = 0;
    none.sums.assign(none.sums.size(), 0);
    EXPECT_TRUE(render::operatorRegions(spec, world, none, 1.0).empty());
}

namespace {

// The phantom's scalar field at world point p (voxels of 1 mm, the grid
// centred on the origin) as the sampler filters it: trilinear, clamped.
float fieldAt(const std::vector<float>& field, glm::ivec3 dims, glm::dvec3 p) {
    const glm::dvec3 pos =
        glm::clamp(p + glm::dvec3(dims) * 0.5 - 0.5, glm::dvec3(0.0), glm::dvec3(dims - 1));
    const glm::ivec3 lo(pos), hi = glm::min(glm::ivec3(pos) + 1, dims - 1);
    const glm::dvec3 f = pos - glm::dvec3(lo);
    double sum = 0.0;
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 v((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
        sum += ((c & 1) ? f.x : 1.0 - f.x) * ((c & 2) ? f.y : 1.0 - f.y) *
               ((c & 4) ? f.z : 1.0 - f.z) *
               field[std::size_t(v.x) + std::size_t(dims.x) * (v.y + std::size_t(dims.y) * v.z)];
    }
    return float(sum);
}

int activeCount(const render::OperatorBlocks& b) {
    return int(std::count(b.active.begin(), b.active.end(), uint8_t(1)));
}

} // namespace

// With the feature field's ranges, a block is active only where a case of
// Eq. 4 can show something (render/skipping/case_occupancy.hpp): every point whose
// case, decided as the shader decides it, shows a visible cell's value lies
// in an active block; and the peel's opening, occupied but neither feature
// nor moved material, is skipped (fewer blocks than without the field).
TEST(OperatorRegions, FeatureBlocksCoverEveryPointWhoseCaseCanShow) {
    const double tau = 3.0;
    const Scene scene =
        sceneWith(kOperators[0], R"({"mode": "surface", "threshold": 30, "depth": 3})");
    const Volume volume = job::loadSceneVolume(scene);
    const glm::ivec3 dims = volume.dims;
    const render::Box box{-glm::dvec3(dims) * 0.5, glm::dvec3(dims) * 0.5};
    const bake::ValueWindow window = job::sceneWindow(scene, volume);
    const render::VisibleValues visible(
        {&scene.transfer}, window, scene.render.classification == Classification::Preintegrated);
    const render::SpanGrid cells = render::spanGrid(volume, window, render::kRayCellVoxels, 2);
    const render::BrickOccupancy bricks =
        render::brickOccupancy(render::brickSpans(cells), box, volume.spacing, visible);
    const std::vector<float> dt =
        bake::distanceFieldCpu(objectMask(volume, 30.0), dims, volume.spacing);
    const bake::FieldRanges ranges = bake::fieldRangesCpu(dt, dims, render::kRayCellVoxels, 2.0f);
    const render::CaseOccupancy cases =
        render::CaseOccupancy::withFeature(bricks, &cells, &visible, &ranges, tau, false);

    // A fine map and a short reach: blocks of about a voxel, so that a case
    // flagged a millimetre off would leave points out.
    OperatorSpec spec = scene.operators.at(0);
    spec.resolution = glm::ivec3(160);
    const operators::WorldBox world{spec.localToWorld,
                                    operators::deformedBounds(spec.params, spec.resolution)};
    const double reach = 0.25;
    const render::OperatorBlocks blocks = render::operatorBlocks(spec, world, cases, reach);
    const render::OperatorBlocks blind =
        render::operatorBlocks(spec, world, render::CaseOccupancy(bricks), reach);
    const render::OperatorBlocks axis =
        render::operatorBlocks(spec, world, render::CaseOccupancy::movedOnly(bricks), reach);
    ASSERT_EQ(blocks.dims, blind.dims);
    for (std::size_t i = 0; i < blind.active.size(); ++i) {
        ASSERT_LE(blocks.active[i], blind.active[i]) << "block " << i; // never adds one
        ASSERT_LE(axis.active[i], blind.active[i]) << "block " << i;
    }
    EXPECT_LT(activeCount(blocks), activeCount(blind) * 9 / 10);
    EXPECT_LT(activeCount(axis), activeCount(blind));

    const auto cellShows = [&](glm::dvec3 p) {
        const glm::ivec3 c =
            glm::clamp(glm::ivec3(glm::floor((p - box.lo) / double(render::kRayCellVoxels))),
                       glm::ivec3(0), cells.cells - 1);
        const render::ValueSpan& s =
            cells.spans[std::size_t(c.x) +
                        std::size_t(cells.cells.x) * (c.y + std::size_t(cells.cells.y) * c.z)];
        return !s.empty() && visible.anyIn(s.low(), s.high());
    };
    const auto inVolume = [&](glm::dvec3 p) {
        return glm::all(glm::greaterThanEqual(p, box.lo)) &&
               glm::all(glm::lessThanEqual(p, box.hi));
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const glm::dvec3 extent = world.local.hi - world.local.lo;
    // Points up to the reach beyond the box too: a slab's back, resolved
    // for the block its front lies in, where the sampler clamps the map.
    const glm::dmat3 axes(spec.localToWorld);
    const glm::dvec3 beyond =
        reach / glm::dvec3(glm::length(axes[0]), glm::length(axes[1]), glm::length(axes[2]));
    int kept = 0, moved = 0;
    for (int n = 0; n < 40000; ++n) {
        const glm::dvec3 q =
            world.local.lo - beyond + glm::dvec3(u(rng), u(rng), u(rng)) * (extent + 2.0 * beyond);
        const glm::vec4 m = sampledMap(spec, world.local, q);
        const glm::dvec3 prime(spec.localToWorld * glm::dvec4(q, 1.0));
        const glm::dvec3 p0(spec.localToWorld * glm::dvec4(q + glm::dvec3(glm::vec3(m)), 1.0));
        const float mPrime = fieldAt(dt, dims, prime) >= tau ? 1.0f : 0.0f;
        const float m0 = fieldAt(dt, dims, p0) >= tau ? 1.0f : 0.0f;
        const int which =
            shader::featureCase(m.w > 0.0f && inVolume(p0), m0, inVolume(prime), mPrime);
        const bool shows = (which == CW_CASE_MASKED && cellShows(prime)) ||
                           (which == CW_CASE_TRANSFORMED && cellShows(p0));
        if (!shows) continue;
        (which == CW_CASE_MASKED ? kept : moved) += 1;
        const glm::ivec3 b = glm::clamp(
            glm::ivec3(glm::floor((q - world.local.lo) / extent * glm::dvec3(spec.resolution))) /
                render::kOperatorBlockTexels,
            glm::ivec3(0), blocks.dims - 1);
        ASSERT_EQ(blocks.active[std::size_t(b.x) + std::size_t(blocks.dims.x) *
                                                       (b.y + std::size_t(blocks.dims.y) * b.z)],
                  1)
            << "q " << q.x << " " << q.y << " " << q.z << " case " << which;
    }
    EXPECT_GT(kept, 1000); // both cases tried
    EXPECT_GT(moved, 1000);
}

namespace {

// How many pixels of `a` and `b` differ by more than 1e-3 in some channel, and
// the largest difference.
std::pair<int, float> seamsBetween(const Image& a, const Image& b) {
    int seams = 0;
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4) {
        float e = 0.0f;
        for (std::size_t c = 0; c < 4; ++c)
            e = std::max(e, std::abs(a.rgba[i + c] - b.rgba[i + c]));
        worst = std::max(worst, e);
        seams += e > 1e-3f;
    }
    return {seams, worst};
}

} // namespace

class OperatorRegionsRender : public GpuTest {};

TEST_F(OperatorRegionsRender, SkippingChangesNoPixel) {
    const std::string alignments[] = {
        "", R"({"mode": "surface", "threshold": 30, "depth": 3, "band": 2})",
        R"({"mode": "segment", "labels": ["brain"], "band": 2})"};
    // Long slabs too: the shader resolves a slab's back and middle, up to a
    // slab beyond the fragment, and the regions must reach that far.
    for (double spacing : {1.0, 6.0})
        for (const char* op : kOperators) {
            for (const std::string& alignment : alignments) {
                const Scene scene = sceneWith(op, alignment, spacing);
                SCOPED_TRACE(scene.operators.at(0).name + " " + alignment + " d " +
                             std::to_string(spacing));
                const auto volume = std::make_shared<const Volume>(job::loadSceneVolume(scene));
                auto labels = job::loadSceneLabels(scene, volume);
                bake::GradientBaker baker(ctx());
                const render::GpuVolume gv = render::prepareVolume(
                    ctx(), baker, volume, job::sceneWindow(scene, *volume), std::nullopt, labels);
                render::VolumeRenderer renderer(ctx());
                renderer.setOperatorSkipping(false);
                const Image whole = renderer.render(scene, gv);
                renderer.setOperatorSkipping(true);
                const Image skipped = renderer.render(scene, gv);
                // The same samples, but a fragment's world position is interpolated
                // over a region's polygon instead of the box's (float rounding,
                // up to 1e-4), and where two regions' polygons meet in a T-junction
                // a pixel centre on the seam can be shaded twice or not at all (as
                // between the volume's brick boxes): a few pixels, one sample
                // each. A region missing would change whole areas. Where the filter
                // quantizes its weights, the rounding moves more samples
                // (expectAgree): up to 307 pixels by up to 0.15 on an H200.
                if (filtersInFloat()) {
                    const auto [seams, worst] = seamsBetween(whole, skipped);
                    EXPECT_LE(seams, 4) << "worst " << worst;
                    EXPECT_LE(worst, 0.02f);
                } else {
                    expectAgree(whole, skipped, 0.0f, "regions");
                }
                // The ray caster steps over the empty blocks: exactly the
                // samples the whole box would make transparent, so no pixel
                // may change at all.
                Scene rays = scene;
                rays.render.method = RenderMethod::Raycast;
                renderer.setOperatorSkipping(false);
                const Image castWhole = renderer.render(rays, gv);
                renderer.setOperatorSkipping(true);
                const Image castSkipped = renderer.render(rays, gv);
                EXPECT_EQ(compareImages(castWhole, castSkipped).maxAbs, 0.0f) << "ray cast";
            }
        }
}

} // namespace cutaway::test
