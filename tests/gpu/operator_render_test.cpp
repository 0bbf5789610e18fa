// Operators rendered on lavapipe: properties from the paper that a wrong
// implementation breaks. Small images and phantoms keep it quick.
#include "bake/operator_bake.hpp"
#include "core/error.hpp"
#include "gpu/resources.hpp"
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "operators/operator_geometry.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"
#include "scene/scene.hpp"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

// The head phantom seen from straight above, orthographic, 48^3 voxels of 1 mm.
Scene topView(int pixels = 48) {
    Scene s = headScene(48, pixels, pixels);
    s.camera.useOrbit = false;
    s.camera.eye = glm::dvec3(0.0, 0.0, 400.0);
    s.camera.target = glm::dvec3(0.0);
    s.camera.up = glm::dvec3(0.0, 1.0, 0.0);
    s.camera.projection = Projection::Orthographic;
    s.camera.orthoHeight = 60.0;
    return s;
}

Scene parsedWith(const std::string& operators, int pixels = 48) {
    Scene s = topView(pixels);
    Scene parsed = parseScene(nlohmann::json::parse(R"({"version": 1, "volume": {"phantom": "head"},
        "operators": )" + operators + "}"),
                              "/nonexistent", "test");
    s.operators = parsed.operators;
    return s;
}

float alpha(const Image& img, int x, int y) {
    return img.pixel(x, y)[3];
}

} // namespace

TEST_F(GpuTest, RetractorOpeningIsEmptySeenStraightIntoIt) {
    // The opening narrows to nothing at the incision's bottom (a wedge), so
    // the box reaches far below the volume (z from -60 to +24 mm): looking
    // straight down into the opening sees no material at all.
    Scene with = parsedWith(R"([{ "type": "retractor",
        "placement": { "translate": [0, 0, -18], "scale": [40, 44, 84] },
        "params": { "length": 44, "depth": 84, "opening": 16 } }])");
    Scene without = topView();
    const Image open = renderScene(ctx(), with);
    const Image closed = renderScene(ctx(), without);
    // Pixel columns of x = 0 (image centre) for |y| < 8 mm: 48 px over 60 mm.
    for (int y = 24 - 8; y <= 24 + 8; ++y) {
        for (int x : {23, 24}) {
            EXPECT_GT(alpha(closed, x, y), 0.9f) << "control: the head is opaque here";
            EXPECT_EQ(alpha(open, x, y), 0.0f) << "pixel " << x << "," << y << " in the opening";
        }
    }
}

TEST_F(GpuTest, IdentityParametersRenderLikeNoOperator) {
    const Image none = renderScene(ctx(), topView());
    for (
        const char* op : {
            R"({ "type": "peeler", "placement": { "translate": [6, 0, 10], "scale": [30, 30, 20] },
                  "params": { "angle": 0 } })",
            R"({ "type": "dilator", "placement": { "translate": [-4, 3, 8], "scale": [30, 30, 30] },
                  "params": { "magnification": 1 } })",
            R"({ "type": "pliers", "placement": { "translate": [0, -5, 12], "scale": [30, 30, 30] },
                  "params": { "displacement": [0, 0, 0] } })",
            R"({ "type": "retractor", "placement": { "scale": [30, 30, 30] },
                  "params": { "opening": 0 } })"}) {
        SCOPED_TRACE(op);
        Scene s = parsedWith(std::string("[") + op + "]");
        s.camera.useOrbit = true; // an oblique view crosses the operator's box faces
        s.camera.azimuthDeg = 35.0;
        s.camera.elevationDeg = 30.0;
        s.camera.distance = 160.0; // fixed: the fit would grow with the operator's box
        s.camera.projection = Projection::Perspective;
        Scene n = s;
        n.operators.clear();
        // The operator path maps through its half-float map and a matrix round
        // trip; the image may differ by float noise only (expectAgree).
        expectAgree(renderScene(ctx(), s), renderScene(ctx(), n), 2e-3f, "identity");
    }
}

TEST_F(GpuTest, TwoOperatorsSideBySideComposeLikeEachAlone) {
    const std::string left = R"({ "type": "retractor",
        "placement": { "translate": [-12, 0, 12], "scale": [20, 30, 24] },
        "params": { "opening": 8 } })";
    const std::string right = R"({ "type": "pliers",
        "placement": { "translate": [12, 0, 12], "scale": [20, 30, 24] },
        "params": { "radius": 9, "displacement": [3, 0, 0] } })";
    const Image a = renderScene(ctx(), parsedWith("[" + left + "]"));
    const Image b = renderScene(ctx(), parsedWith("[" + right + "]"));
    const Image both = renderScene(ctx(), parsedWith("[" + left + "," + right + "]"));
    const Image none = renderScene(ctx(), topView());
    // Seen from above the two boxes project to disjoint regions, so each pixel
    // of `both` is that of `a`, of `b`, or of neither: both = a + b - none.
    float worst = 0.0f, changedA = 0.0f, changedB = 0.0f;
    for (std::size_t i = 0; i < both.rgba.size(); ++i) {
        worst = std::max(worst, std::abs(both.rgba[i] - (a.rgba[i] + b.rgba[i] - none.rgba[i])));
        changedA = std::max(changedA, std::abs(a.rgba[i] - none.rgba[i]));
        changedB = std::max(changedB, std::abs(b.rgba[i] - none.rgba[i]));
    }
    EXPECT_GT(changedA, 0.1f) << "the retractor should change the image";
    EXPECT_GT(changedB, 0.05f) << "the pliers should change the image";
    EXPECT_LE(worst, 1e-4f) << "a region drawn twice or not at all";
}

TEST_F(GpuTest, OverlappingOperatorsAreRefusedNamingBoth) {
    Scene s = parsedWith(R"([
        { "type": "retractor", "name": "left cut", "placement": { "translate": [-5, 0, 0], "scale": [20, 20, 20] } },
        { "type": "pliers", "name": "grab", "placement": { "translate": [5, 0, 0], "scale": [20, 20, 20] } }])");
    try {
        renderScene(ctx(), s);
        FAIL() << "expected overlapping operators to be refused";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("left cut"), std::string::npos) << what;
        EXPECT_NE(what.find("grab"), std::string::npos) << what;
        EXPECT_NE(what.find("overlap"), std::string::npos) << what;
    }
}

TEST_F(GpuTest, OperatorBakeMatchesTheSharedHeaderOnTheCpu) {
    Scene s = parsedWith(R"([
        { "type": "peeler", "placement": { "scale": [40, 40, 20] }, "params": { "angle": 150, "hinge": -5 } },
        { "type": "retractor", "placement": { "translate": [100, 0, 0], "scale": [40, 40, 40] } },
        { "type": "pliers", "placement": { "translate": [200, 0, 0], "scale": [40, 40, 40] },
          "params": { "radius": 15, "displacement": [4, -2, 5] } },
        { "type": "dilator", "placement": { "translate": [300, 0, 0], "scale": [40, 40, 40] },
          "params": { "radius": 6, "magnification": 2.5 } }])");
    bake::OperatorBaker baker(ctx());
    for (const OperatorSpec& op : s.operators) {
        SCOPED_TRACE(op.name);
        const glm::ivec3 dims(20, 17, 16);
        const operators::LocalBox box = operators::deformedBounds(op.params, dims);
        const shader::OperatorParams params = operators::sampledParams(op.params, box, dims);
        const bake::BakedMap baked = baker.bake(params, glm::vec3(box.lo), glm::vec3(box.hi), dims);
        const auto bytes =
            gpu::downloadImage(ctx(), baked.map, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 8);
        const auto* halves = reinterpret_cast<const uint16_t*>(bytes.data());
        float worst = 0.0f;
        for (int z = 0; z < dims.z; ++z)
            for (int y = 0; y < dims.y; ++y)
                for (int x = 0; x < dims.x; ++x) {
                    const glm::vec3 q = glm::mix(glm::vec3(box.lo), glm::vec3(box.hi),
                                                 (glm::vec3(x, y, z) + 0.5f) / glm::vec3(dims));
                    glm::vec4 expected = shader::operatorBackward(q, params);
                    expected = glm::vec4(glm::vec3(expected) - q, expected.w);
                    const std::size_t t = 4 * std::size_t(x + dims.x * (y + dims.y * z));
                    for (int c = 0; c < 4; ++c) {
                        const float got = glm::unpackHalf1x16(halves[t + std::size_t(c)]);
                        const float e = expected[c];
                        // Half precision: 2^-11 relative, plus GPU vs CPU float math.
                        worst = std::max(worst, std::abs(got - e) / (1.0f + std::abs(e)));
                    }
                }
        EXPECT_LE(worst, 2e-3f);

        // The derivatives, at half the map's resolution: per axis i, in
        // section i, the mean over the 2x2x2 map texels a half texel covers
        // (clamped at the far faces) of their central differences over one
        // texel along i (one-sided at the faces), per local unit. 17 map
        // texels along y: the last half texel covers one row, twice.
        const auto derivativeBytes = gpu::downloadImage(
            ctx(), baked.derivatives, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 8);
        const glm::ivec3 half = bake::derivativeDims(dims);
        ASSERT_EQ(half, glm::ivec3(10, 9, 8));
        ASSERT_EQ(derivativeBytes.size(), std::size_t(3 * half.x * half.y * half.z) * 8);
        const auto* derivatives = reinterpret_cast<const uint16_t*>(derivativeBytes.data());
        const auto mapAt = [&](glm::ivec3 v, int c) {
            return glm::unpackHalf1x16(
                halves[4 * std::size_t(v.x + dims.x * (v.y + dims.y * v.z)) + std::size_t(c)]);
        };
        const glm::vec3 texel = glm::vec3(box.hi - box.lo) / glm::vec3(dims);
        const auto centralDifference = [&](glm::ivec3 v, int axis, int c) {
            glm::ivec3 lo = v, hi = v;
            lo[axis] = std::max(v[axis] - 1, 0);
            hi[axis] = std::min(v[axis] + 1, dims[axis] - 1);
            const float span = float(hi[axis] - lo[axis]) * texel[axis];
            return (mapAt(hi, c) - mapAt(lo, c)) / span;
        };
        float worstDerivative = 0.0f, largest = 0.0f;
        for (int axis = 0; axis < 3; ++axis)
            for (int z = 0; z < half.z; ++z)
                for (int y = 0; y < half.y; ++y)
                    for (int x = 0; x < half.x; ++x) {
                        const std::size_t t =
                            4 * std::size_t(x + half.x * axis + 3 * half.x * (y + half.y * z));
                        for (int c = 0; c < 4; ++c) {
                            float e = 0.0f;
                            for (int corner = 0; corner < 8; ++corner) {
                                const glm::ivec3 v = glm::min(
                                    2 * glm::ivec3(x, y, z) +
                                        glm::ivec3(corner & 1, (corner >> 1) & 1, corner >> 2),
                                    dims - 1);
                                e += centralDifference(v, axis, c) / 8.0f;
                            }
                            const float got = glm::unpackHalf1x16(derivatives[t + std::size_t(c)]);
                            worstDerivative =
                                std::max(worstDerivative, std::abs(got - e) / (1.0f + std::abs(e)));
                            largest = std::max(largest, std::abs(e));
                        }
                    }
        EXPECT_LE(worstDerivative, 2e-3f);
        EXPECT_GT(largest, 0.05f) << "the operator moves nothing: the check would be empty";
    }
}

TEST_F(GpuTest, MovingAnOperatorDoesNotRebakeItsMap) {
    const auto volume = job::loadSceneVolume(topView());
    bake::GradientBaker gradients(ctx());
    const render::GpuVolume gv = render::prepareVolume(
        ctx(), gradients, std::make_shared<Volume>(volume), job::sceneWindow(topView(), volume));
    render::VolumeRenderer renderer(ctx());
    Scene s = parsedWith(
        R"([{ "type": "retractor", "placement": { "translate": [0, 0, 10], "scale": [20, 20, 20] } }])");
    renderer.render(s, gv);
    EXPECT_EQ(renderer.lastStats().operatorBakes, 1);
    s.operators[0].localToWorld[3].x += 5.0; // moved: same map
    renderer.render(s, gv);
    EXPECT_EQ(renderer.lastStats().operatorBakes, 1);
    s.operators[0].params.a.z *= 0.5f; // a narrower opening: a new map
    renderer.render(s, gv);
    EXPECT_EQ(renderer.lastStats().operatorBakes, 2);
}

} // namespace cutaway::test

namespace cutaway::test {

TEST_F(GpuTest, SequentialCompositionRendersOverlappingOperators) {
    const std::string ops = R"([
        { "type": "retractor", "placement": { "translate": [0, 0, 12], "scale": [30, 40, 24] },
          "params": { "opening": 10 } },
        { "type": "dilator", "placement": { "translate": [4, 0, 10], "scale": [20, 20, 20] },
          "params": { "magnification": 1 } }])";
    Scene separate = parsedWith(ops);
    EXPECT_THROW(renderScene(ctx(), separate), InputError) << "overlap must be refused";

    Scene sequential = separate;
    sequential.render.composition = Composition::Sequential;
    Scene retractorOnly = separate;
    retractorOnly.operators.resize(1);
    Scene none = separate;
    none.operators.clear();
    // The first operator is baked into an intermediate volume on the CPU (its
    // exact values are checked by the export tests); here: it is rendered at
    // all. Inside the retractor's footprint the sequential image must depart
    // from the untouched head about as much as the retractor alone does. The
    // two differ at the walls: the intermediate volume has a 1 mm staircase
    // wall shaded by its own gradients, the live map blends toward the cut
    // normal (Eq. 7); measured on lavapipe, the sequential image departs from
    // the untouched head by 0.69 times the retractor's own departure (0 if the
    // first operator were dropped).
    const Image retractor = job::renderImage(ctx(), retractorOnly);
    const Image seq = job::renderImage(ctx(), sequential);
    const Image untouched = job::renderImage(ctx(), none);
    auto rgbDiff = [](const Image& a, const Image& b, std::size_t i) {
        return std::abs(a.rgba[i] - b.rgba[i]) + std::abs(a.rgba[i + 1] - b.rgba[i + 1]) +
               std::abs(a.rgba[i + 2] - b.rgba[i + 2]);
    };
    double effect = 0.0, departure = 0.0;
    int footprint = 0;
    for (std::size_t i = 0; i < retractor.rgba.size(); i += 4) {
        if (rgbDiff(retractor, untouched, i) < 0.15f) continue;
        ++footprint;
        effect += rgbDiff(retractor, untouched, i);
        departure += rgbDiff(seq, untouched, i);
    }
    ASSERT_GT(footprint, 20) << "the retractor should open the head";
    EXPECT_GT(departure, 0.4 * effect) << footprint << " pixels";
    EXPECT_LT(departure, 1.6 * effect) << footprint << " pixels";

    // operator_id names the live operator by its index in the scene: 1.
    sequential.output.operatorId = true;
    const Image ids = job::renderImage(ctx(), sequential);
    int live = 0;
    for (float v : ids.operatorIds) {
        ASSERT_TRUE(v == -2.0f || v == -1.0f || v == 1.0f) << v;
        live += v == 1.0f;
    }
    EXPECT_GT(live, 20) << "the dilator's box shows moved samples";
}

} // namespace cutaway::test

namespace cutaway::test {

TEST_F(GpuTest, OperatorIdChannelNamesTheFirstVisibleSamplesOperator) {
    Scene s = parsedWith(R"([
        { "type": "retractor", "placement": { "translate": [-12, 0, 12], "scale": [20, 30, 24] },
          "params": { "opening": 8 } },
        { "type": "pliers", "placement": { "translate": [12, 0, 12], "scale": [20, 30, 24] },
          "params": { "radius": 9, "displacement": [3, 0, 0] } }])");
    const Image plain = renderScene(ctx(), s);
    s.output.operatorId = true;
    const Image img = renderScene(ctx(), s);
    ASSERT_EQ(img.operatorIds.size(), std::size_t(img.width * img.height));
    EXPECT_EQ(img.rgba, plain.rgba) << "the id target must not change the picture";

    // 48 px over 60 mm, centred, +y up: pixel (x, y) -> world ((x + 0.5) * 1.25 - 30,
    // 30 - (y + 0.5) * 1.25). The boxes cover x in [-22, -2] and [2, 22], |y| < 15.
    auto id = [&](int x, int y) { return img.operatorIds[std::size_t(y * img.width + x)]; };
    EXPECT_EQ(id(0, 0), -2.0f) << "a corner sees nothing";
    EXPECT_EQ(id(14, 24), 0.0f)
        << "world (-11.9, 0.6): inside the retractor's box, seen from above";
    EXPECT_EQ(id(33, 24), 1.0f) << "world (11.9, 0.6): inside the pliers' box";
    EXPECT_EQ(id(24, 24), -1.0f) << "world (0.6, -0.6): the head between the two boxes";
    int counts[4] = {0, 0, 0, 0};
    for (float v : img.operatorIds) {
        ASSERT_TRUE(v == -2.0f || v == -1.0f || v == 0.0f || v == 1.0f) << v;
        ++counts[static_cast<int>(v) + 2];
    }
    for (int c : counts)
        EXPECT_GT(c, 20);
}

} // namespace cutaway::test

namespace cutaway::test {

// A face seen obliquely crosses the slabs: kept or dropped whole, they show
// on it as contour lines one slice apart, which no finer map removes. Clipped
// where the quantity that empties them changes sign (w at a cut, M where the
// feature stays behind), with Eq. 7's weight averaged over each slab, the
// face converges as the slices get finer. The measure, over the peeler's
// footprint: mean |spacing 1 - spacing 0.25| over the mean change the peeler
// makes, both summed over RGB. On a homogeneous, half-transparent block (40
// mm, no gradient inside), so the flap's faces and the hole are all there is.
double sliceConvergence(const gpu::Context& ctx, const std::string& alignment) {
    Volume block = Volume::allocate(glm::ivec3(48), VoxelType::U8);
    for (int z = 4; z < 44; ++z)
        for (int y = 4; y < 44; ++y)
            for (int x = 4; x < 44; ++x)
                block.data[block.index(x, y, z)] = std::byte{150};
    Scene peeled = parsedWith(R"([{ "type": "peeler",
        "placement": { "translate": [0, 0, 14], "scale": [22, 18, 10] },
        "params": { "hinge": -8, "thickness": 7, "radius": 3, "angle": 130, "width": 24 },
        "alignment": )" + alignment +
                                  "}]",
                              128);
    peeled.camera.eye = glm::dvec3(-150.0, -250.0, 300.0);
    peeled.camera.target = glm::dvec3(4.0, 0.0, 16.0);
    peeled.camera.orthoHeight = 32.0;
    Scene untouched = peeled;
    untouched.operators.clear();
    const Image solid = renderVolume(ctx, untouched, block);
    peeled.render.sliceSpacing = 1.0;
    const Image coarse = renderVolume(ctx, peeled, block);
    peeled.render.sliceSpacing = 0.25;
    const Image fine = renderVolume(ctx, peeled, block);
    double error = 0.0, effect = 0.0;
    int footprint = 0;
    for (std::size_t i = 0; i < fine.rgba.size(); i += 4) {
        double change = 0.0, e = 0.0;
        for (std::size_t c = 0; c < 3; ++c) {
            change += std::abs(fine.rgba[i + c] - solid.rgba[i + c]);
            e += std::abs(coarse.rgba[i + c] - fine.rgba[i + c]);
        }
        if (change < 0.1) continue;
        ++footprint;
        effect += change;
        error += e;
    }
    EXPECT_GT(footprint, 1000) << "the flap should be in view";
    return footprint > 0 ? error / effect : 1.0;
}

// Measured on lavapipe: 0.18 clipped, 0.29 with slabs kept or dropped whole.
TEST_F(GpuTest, CutFacesConvergeAsTheSlicesGetFiner) {
    EXPECT_LT(sliceConvergence(ctx(), R"({ "mode": "axis" })"), 0.23);
}

// The flap takes only the top 3 mm, the rest stays in place: the flap's
// underside and the hole's floor are where M crosses 0.5, over a ramp 1 mm
// wide. Measured on lavapipe: 0.39 clipped, 0.48 kept or dropped whole.
TEST_F(GpuTest, FacesTheFeatureLeavesConvergeAsTheSlicesGetFiner) {
    const char* surface = R"({ "mode": "surface", "threshold": 100, "depth": 3, "band": 0.5 })";
    EXPECT_LT(sliceConvergence(ctx(), surface), 0.43);
}

} // namespace cutaway::test
