// Where along the rays the samples lie (shaders/shared/sampling.h):
// /render/jitter shifts each pixel's samples by its own fraction of the
// spacing, /render/samples averages passes with evenly spread offsets,
// /render/seed varies the offsets between frames. Checked: the jitter turns
// the slices' rings into noise fine enough to average out over a few pixels
// (control: the same scene unjittered), passes bring the picture closer to a
// converged one (control: one pass), reruns stay bit-identical while another
// seed moves the noise, and slicing and ray casting still take the same
// samples with it on.
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "scene/animation.hpp"
#include "scene/scene.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

using nlohmann::json;

// The head phantom's skin and skull as near-surfaces, lit, seen from close
// by (a voxel is about three pixels wide), slices a voxel apart: rings
// several pixels wide. Slabs are taken whole (refine 1): sub-slabs
// (tests/gpu/refine_test.cpp) take most of the rings away themselves.
json ringScene() {
    return {
        {"version", 1},
        {"volume", {{"phantom", "head"}, {"size", {64, 64, 64}}}},
        {"transfer", json::parse(R"({"points": [{"value": 0, "color": [0.9, 0.7, 0.6], "alpha": 0},
              {"value": 50, "color": [0.9, 0.7, 0.6], "alpha": 0},
              {"value": 70, "color": [0.9, 0.7, 0.6], "alpha": 0.6},
              {"value": 200, "color": [1, 1, 0.9], "alpha": 0.9}]})")},
        {"camera", {{"orbit", {{"azimuth", 30}, {"elevation", 35}, {"distance", 90}}}}},
        {"lights",
         {{"ambient", 0.2},
          {"headlight", 0.5},
          {"directional", {{{"direction", {-1, 1, -1}}, {"intensity", 0.6}}}}}},
        {"render",
         {{"size", {128, 128}},
          {"slice_spacing", 1.0},
          {"termination_opacity", 1.0},
          {"refine", 1}}},
    };
}

Image render(const gpu::Context& ctx, const json& document) {
    return job::renderImage(ctx, parseScene(document, "/nonexistent", "test"));
}

json with(json document, const char* key, json value) {
    document["render"][key] = std::move(value);
    return document;
}

// The error left once each 4x4 block of pixels is averaged: what a reader
// sees from a step back. Fine noise averages out; rings and bias do not.
double blockRms(const Image& a, const Image& b) {
    double sum = 0.0;
    int blocks = 0;
    for (int by = 0; by + 4 <= a.height; by += 4)
        for (int bx = 0; bx + 4 <= a.width; bx += 4)
            for (int c = 0; c < 3; ++c) {
                double mean = 0.0;
                for (int y = by; y < by + 4; ++y)
                    for (int x = bx; x < bx + 4; ++x)
                        mean += a.pixel(x, y)[c] - b.pixel(x, y)[c];
                mean /= 16.0;
                sum += mean * mean;
                ++blocks;
            }
    return std::sqrt(sum / blocks);
}

// How alike neighbouring pixels' errors are: the correlation of the error
// (luminance-free: the sum over R, G, B) with the error of the pixel to the
// right. Rings and bias, a few pixels wide, give near 1; fine noise near 0.
double neighbourCorrelation(const Image& a, const Image& b) {
    auto error = [&](int x, int y) {
        double e = 0.0;
        for (int c = 0; c < 3; ++c)
            e += a.pixel(x, y)[c] - b.pixel(x, y)[c];
        return e;
    };
    double cross = 0.0, self = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x + 1 < a.width; ++x) {
            cross += error(x, y) * error(x + 1, y);
            self += error(x, y) * error(x, y);
        }
    return self > 0.0 ? cross / self : 0.0;
}

class Sampling : public GpuTest {
protected:
    Image converged() { return render(ctx(), with(ringScene(), "slice_spacing", 0.25)); }
};

TEST_F(Sampling, JitterTurnsRingsIntoNoiseThatAveragesOut) {
    const Image reference = converged();
    const Image rings = render(ctx(), ringScene());
    const Image jittered = render(ctx(), with(ringScene(), "jitter", true));
    // Rings: neighbouring pixels err alike. Jittered: the error is noise a
    // pixel wide. Measured on lavapipe: 0.43 against -0.01.
    const double ringCorrelation = neighbourCorrelation(rings, reference);
    const double jitterCorrelation = neighbourCorrelation(jittered, reference);
    EXPECT_GT(ringCorrelation, 0.3) << "control: the slices' rings must show at this spacing";
    EXPECT_LT(std::abs(jitterCorrelation), 0.1) << "rings " << ringCorrelation;
    // And it averages out: what is left over 4x4 blocks shrinks (measured
    // 6.0e-3 against 4.5e-3; the rest is the coarse slabs' bias, which no
    // offset removes).
    const double ringError = blockRms(rings, reference);
    const double jitterError = blockRms(jittered, reference);
    EXPECT_LT(jitterError, 0.85 * ringError)
        << "rings " << ringError << ", jittered " << jitterError;
}

TEST_F(Sampling, PassesComeCloserToTheConvergedPicture) {
    const Image reference = converged();
    const json jittered = with(ringScene(), "jitter", true);
    const ImageDiff one = compareImages(render(ctx(), jittered), reference);
    const ImageDiff four = compareImages(render(ctx(), with(jittered, "samples", 4)), reference);
    // Four passes sample the slab at four evenly spread depths: the error of
    // one pass shrinks by a third or more (measured on lavapipe: 9.2e-3
    // against 5.2e-3; control: one pass, against the same reference).
    EXPECT_LT(four.rms, 0.7 * one.rms) << "one pass " << one.rms << ", four " << four.rms;
}

TEST_F(Sampling, RerunsAreBitIdenticalAndTheSeedMovesTheNoise) {
    const json scene = with(with(ringScene(), "jitter", true), "samples", 2);
    const Image first = render(ctx(), scene);
    const Image again = render(ctx(), scene);
    ASSERT_EQ(first.rgba.size(), again.rgba.size());
    EXPECT_EQ(first.rgba, again.rgba) << "the same scene must give the same pixels";
    // The default seed is the frame: frame 0 of a scene is seed 0.
    EXPECT_EQ(render(ctx(), with(scene, "seed", 0)).rgba, first.rgba);
    // Control: another seed, other offsets, other pixels.
    EXPECT_GT(compareImages(render(ctx(), with(scene, "seed", 5)), first).maxAbs, 1e-3f);
}

TEST_F(Sampling, EachFrameOfASequenceTakesItsOwnOffsets) {
    json document = with(ringScene(), "jitter", true);
    document["animation"] = {{"frames", {0, 2}}};
    const Scene scene = parseScene(document, "/nonexistent", "test");
    const Image frame1 = job::renderImage(ctx(), sceneAtFrame(scene, 1));
    const Image frame2 = job::renderImage(ctx(), sceneAtFrame(scene, 2));
    // Nothing moves between the frames but the noise.
    EXPECT_GT(compareImages(frame1, frame2).maxAbs, 1e-3f);
    EXPECT_EQ(render(ctx(), with(document, "seed", 2)).rgba, frame2.rgba);
}

TEST_F(Sampling, SlicingAndRayCastingTakeTheSameJitteredSamples) {
    // The scene of tests/gpu/raycast_test.cpp (a gentler transfer function,
    // seen from farther) with a directional light.
    json scene = with(with(ringScene(), "jitter", true), "samples", 2);
    scene["transfer"] =
        json::parse(R"({"points": [{"value": 0, "color": [0.9, 0.7, 0.6], "alpha": 0},
          {"value": 60, "color": [0.9, 0.7, 0.6], "alpha": 0.05},
          {"value": 200, "color": [1, 1, 0.9], "alpha": 0.8}]})");
    scene["camera"]["orbit"]["distance"] = 220;
    scene["render"]["size"] = {80, 72};
    scene["labels"] = {{"phantom", true}};
    scene["render"]["background"] = "transparent";
    const Image sliced = render(ctx(), with(scene, "method", "slicing"));
    const Image cast = render(ctx(), with(scene, "method", "raycast"));
    // The equivalence bound of tests/gpu/raycast_test.cpp, jitter on.
    expectAgree(sliced, cast, 4e-3f, "jittered, two passes"); // measured 3.0e-3
    // Control: unjittered slices against jittered rays differ.
    EXPECT_GT(
        compareImages(render(ctx(), with(with(scene, "jitter", false), "method", "slicing")), cast)
            .maxAbs,
        2e-2f);
}

TEST_F(Sampling, OperatorsTakeTheJitteredSamplesInBothMethods) {
    for (const json& operators : phantomOperatorCases()) {
        json scene = operatorPhantomDocument();
        scene["operators"] = operators;
        scene["render"]["jitter"] = true;
        scene["render"]["termination_opacity"] = 1.0;
        const Image sliced = render(ctx(), with(scene, "method", "slicing"));
        const Image cast = render(ctx(), with(scene, "method", "raycast"));
        // The bound of tests/gpu/raycast_operators_test.cpp: a mean below
        // 1e-3 (a cut face's pixels may differ by rounding where the
        // slab is clipped).
        if (!filtersInFloat()) {
            expectAgree(sliced, cast, 0.0f, operators.dump());
            continue;
        }
        EXPECT_LT(compareImages(sliced, cast).meanAbs, 1e-3) << operators.dump();
    }
}

} // namespace
} // namespace cutaway::test
