// `cutaway export` writes the volume the render shows: the exported volume
// rendered without its operator looks like the scene rendered with it, for
// aligned operators too (their distance field and segment mask are made on
// the CPU for the export, baked on the device for the render).
#include "gpu_fixture.hpp"
#include "job/export_volume.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

using nlohmann::json;

// The operator tests' head phantom, unlit (so normals, which the render
// carries through the map's Jacobian and the export takes from its own
// grid, do not count), a fixed camera distance and window (the export's
// volume is larger and its values a resampling of the scan's), and a peeler
// over the crown that reaches into the brain. Cuts as each pixel's ray
// sees them (cut_antialias 0): the export is a grid of voxels, which cannot
// hold a coverage taken over the render's pixels.
json peeledHead(const json& alignment) {
    json doc = operatorPhantomDocument();
    doc["volume"]["window"] = {0, 255};
    doc["render"]["cut_antialias"] = 0;
    doc["camera"]["orbit"] = {{"azimuth", 270}, {"elevation", 70}, {"distance", 190}};
    doc["render"]["size"] = {128, 128};
    doc["render"]["shading"] = {{"enabled", false}};
    doc["operators"] = json::array({{
        {"type", "peeler"},
        {"placement", {{"translate", {0, 0, 16}}, {"scale", {50, 50, 30}}}},
        {"alignment", alignment},
        {"params", {{"hinge", -10}, {"thickness", 24}, {"radius", 4}, {"angle", 160}}},
    }});
    return doc;
}

// PSNR of `a` against `b` over the pixels whose first visible sample came
// from operator 0 in `a` (its operator ids), measured as comparePictures
// measures a whole picture: linear RGB clipped to [0, 1], encoded with gamma
// 1/2.2. `pixels` receives how many there were.
double operatorRegionPsnr(const Image& a, const Image& b, int& pixels) {
    double sum = 0.0;
    pixels = 0;
    for (std::size_t i = 0; i < a.operatorIds.size(); ++i) {
        if (a.operatorIds[i] != 0.0f) continue;
        ++pixels;
        for (int c = 0; c < 3; ++c) {
            const auto encode = [](float v) {
                return std::pow(std::clamp(v, 0.0f, 1.0f), 1 / 2.2f);
            };
            const double d = encode(a.rgba[4 * i + c]) - encode(b.rgba[4 * i + c]);
            sum += d * d;
        }
    }
    return pixels == 0 ? 0.0 : 10.0 * std::log10(3.0 * pixels / std::max(sum, 1e-30));
}

class ExportRender : public GpuTest {
protected:
    struct Pair {
        Image rendered; // the scene with its operator
        Image exported; // its export, rendered without one
    };
    Pair renderBoth(const json& alignment, bool lit = false, int oversample = 1) {
        json doc = peeledHead(alignment);
        if (lit) doc["render"]["shading"] = {{"enabled", true}, {"specular", 0.0}};
        doc["output"]["operator_id"] = true;
        Scene scene = parseScene(doc, "/nonexistent", "export render");
        Pair p;
        p.rendered = job::renderImage(ctx(), scene);
        const Volume deformed = job::exportVolume(scene, false, oversample).volume;
        // The renderer centres a volume on the origin; the export's grid grew
        // (the flap rises above the scan), so the camera looks at where the
        // scan's centre now lies.
        const Volume scan = job::loadSceneVolume(scene);
        // Origins are voxel centres: the boxes begin half a voxel before them.
        const glm::dvec3 shift = deformed.origin - scan.origin +
                                 0.5 * (scan.spacing - deformed.spacing) +
                                 0.5 * (deformed.extent() - scan.extent());
        Scene plain = scene;
        plain.operators.clear();
        plain.camera.target -= shift;
        // The same slabs, and the same opacity per mm: both are in voxels of
        // the volume rendered unless given.
        plain.render.sliceSpacing *= oversample;
        plain.unitDistance = std::min({scan.spacing.x, scan.spacing.y, scan.spacing.z});
        p.exported = renderVolume(ctx(), plain, deformed);
        return p;
    }
};

// --oversample: inside the operator's region (the pixels whose first visible
// sample the live render took from the operator) the export rendered comes
// closer to the live render, its cut walls resolved finer. Measured on
// lavapipe, unlit, in dB: axis-aligned 33.5 at K = 1, 38.0 at 2, 41.6 at 3;
// surface-aligned 29.2, 33.3, 34.8. Each must gain 3 dB from 1 to 2 (its
// control: the same comparison at K = 1); K = 2 keeps the CPU resampling
// within the sanitized suite's time.
TEST_F(ExportRender, OversampledExportsComeCloserInsideTheOperator) {
    for (const json& alignment :
         {json{{"mode", "axis"}}, json{{"mode", "surface"}, {"depth", 3}, {"band", 1}}}) {
        int pixels = 0;
        const Pair coarse = renderBoth(alignment, false, 1);
        const double one = operatorRegionPsnr(coarse.rendered, coarse.exported, pixels);
        EXPECT_GT(pixels, 2000) << alignment.dump() << ": the operator shows";
        const Pair fine = renderBoth(alignment, false, 2);
        const double two = operatorRegionPsnr(fine.rendered, fine.exported, pixels);
        EXPECT_GT(two, one + 3.0) << alignment.dump() << ": K = 1 " << one;
    }
}

// Mean absolute differences per channel. The export resamples the moved
// material onto a grid that the render then samples again, and the render
// resolves cut faces through a baked map where the export is exact: the
// axis-aligned pair differs by 0.005, the aligned pairs by 0.005-0.006, and
// an export that ignored the alignment by 0.068-0.071 (the flap folded to
// 160 degrees, seen from beyond its hinge). The features are solid (the
// brain; what lies 3 mm under the skin). A thin shell kept in place, the
// skull, differed by 0.016 in an earlier view of this test: the shell's
// bared surface renders through the operator with specks that the export's
// grid smooths away.
TEST_F(ExportRender, TheExportedVolumeLooksLikeTheRender) {
    const Pair axis = renderBoth({{"mode", "axis"}});
    EXPECT_LT(compareImages(axis.rendered, axis.exported).meanAbs, 0.015);
    for (const json& alignment : {json{{"mode", "surface"}, {"depth", 3}, {"band", 1}},
                                  json{{"mode", "segment"}, {"labels", {"brain"}}}}) {
        const Pair aligned = renderBoth(alignment);
        const double same = compareImages(aligned.rendered, aligned.exported).meanAbs;
        // What an export that ignored the alignment would be off by.
        const double ignored = compareImages(aligned.rendered, axis.exported).meanAbs;
        EXPECT_GT(ignored, 0.04) << alignment.dump() << ": control, the alignment shows";
        EXPECT_LT(same, 0.015) << alignment.dump();
        EXPECT_LT(same, 0.25 * ignored) << alignment.dump();
    }
}

// Lit, the moved material's normals come from the render's Jacobian of the
// map (Eq. 5, from the map's baked derivatives) and from the export's own
// grid: the pair differs by 0.0081 (unlit: 0.0049). Measured with the
// Jacobian left out (the identity): 0.022; with its columns taken from the
// wrong axes: 0.026. Diffuse light only, so highlights do not weigh a
// normal's error more where they fall.
TEST_F(ExportRender, MovedMaterialIsLitAsTheExportIs) {
    const Pair lit = renderBoth({{"mode", "axis"}}, true);
    const Pair unlit = renderBoth({{"mode", "axis"}}, false);
    EXPECT_GT(compareImages(lit.exported, unlit.exported).meanAbs, 0.05) << "control: lit";
    EXPECT_LT(compareImages(lit.rendered, lit.exported).meanAbs, 0.012);
}

} // namespace
} // namespace cutaway::test
