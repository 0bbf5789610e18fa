#pragma once
// Base of every test that touches a Vulkan device: one context per test with
// the Khronos validation layer on; any validation message fails the test.
#include "gpu/context.hpp"
#include "gpu/resources.hpp"
#include "io/image.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <gtest/gtest.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cutaway::test {

/// Largest absolute per-channel difference, and the root mean square one.
struct ImageDiff {
    float maxAbs = 0.0f;
    double rms = 0.0;
    double meanAbs = 0.0;
};
ImageDiff compareImages(const Image& a, const Image& b);

/// How closely two renders must agree that take the same samples up to float
/// rounding of their positions (computed two ways: interpolated over another
/// polygon, by a ray, through an operator's map), in GpuTest::expectAgree.
/// Where the filter weighs texels in float, such a rounding moves a sample's
/// value by float noise, and the images agree pixel for pixel to a tolerance
/// each test states. Where it quantizes the weights to 8 bits, the same
/// rounding can move a sample's value by 2^-8 of the step between two voxels,
/// and a steep transfer function turns that into a jump in a handful of
/// pixels. Measured on an NVIDIA H200 in the comparisons of tests/gpu:
/// rms up to 2.5e-3, single pixels up to 0.38 (post-classified). There the
/// images must agree in rms, and no pixel may differ by more than
/// kQuantizedMaxAbs; a region missing or shaded wrong changes whole areas and
/// the rms with them (each test that can fail so checks the rms it would see).
constexpr float kQuantizedMaxAbs = 0.5f;
constexpr double kQuantizedRms = 3e-3;

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override {
        gpu::ContextOptions options;
        options.validation = true;
        m_ctx = std::make_unique<gpu::Context>(options);
    }
    void TearDown() override {
        if (!m_ctx) return;
        for (const auto& m : m_ctx->validationMessages())
            ADD_FAILURE() << m;
        EXPECT_EQ(m_ctx->validationMessageCount(), 0u) << "validation layer messages";
        m_ctx.reset();
    }
    const gpu::Context& ctx() const { return *m_ctx; }

    /// Whether the device weighs texels in float when it filters: lavapipe, a
    /// CPU implementation, does for 16-bit and float formats. GPUs quantize the
    /// weights to subTexelPrecisionBits (8 on NVIDIA).
    bool filtersInFloat() const;
    /// Checks that `a` and `b` agree as renders of the same samples do: to
    /// `precise` in every channel where the filter weighs in float, else as
    /// kQuantizedRms (or `quantizedRms`, where a test measured more) and
    /// kQuantizedMaxAbs say.
    void expectAgree(const Image& a, const Image& b, float precise, const std::string& what,
                     double quantizedRms = kQuantizedRms) const;

    std::unique_ptr<gpu::Context> m_ctx;
};

/// A scene on the head phantom with a transfer function that shows skin,
/// skull and brain, a front orbit view and only a headlight (symmetric).
Scene headScene(int phantomSize, int width, int height);

/// A scene document on the 64^3 head phantom with its labels, a transfer
/// function that shows skin, brain and skull translucently, a view from above
/// and in front, 96x96 over a transparent background: the operator tests'.
nlohmann::json operatorPhantomDocument();

/// The `operators` arrays that tests of a shader path render on
/// operatorPhantomDocument: none, a surface-aligned peeler and a
/// segment-aligned retractor.
std::vector<nlohmann::json> phantomOperatorCases();

/// A baked R16F field in the feature bakes' layout (distance field, segment
/// mask, operator-region field), downloaded as floats in x-fastest order.
std::vector<float> downloadFeatureField(const gpu::Context& ctx, const gpu::Image& image);

/// Renders a scene to an image (loads its volume, prepares, renders).
Image renderScene(const gpu::Context& ctx, const Scene& scene);

/// Renders a scene of an explicit volume (not from the scene's source).
Image renderVolume(const gpu::Context& ctx, const Scene& scene, const Volume& volume);

} // namespace cutaway::test
