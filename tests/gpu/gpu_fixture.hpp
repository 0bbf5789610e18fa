#pragma once
// Base of every test that touches a Vulkan device: one context per test with
// the Khronos validation layer on; any validation message fails the test.
#include "gpu/context.hpp"
#include "io/image.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <gtest/gtest.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace cutaway::test {

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

    std::unique_ptr<gpu::Context> m_ctx;
};

/// A scene on the head phantom with a transfer function that shows skin,
/// skull and brain, a front orbit view and only a headlight (symmetric).
Scene headScene(int phantomSize, int width, int height);

/// A scene document on the 64^3 head phantom with its labels, a transfer
/// function that shows skin, brain and skull translucently, a view from above
/// and in front, 96x96 over a transparent background: the operator tests'.
nlohmann::json operatorPhantomDocument();

/// Renders a scene to an image (loads its volume, prepares, renders).
Image renderScene(const gpu::Context& ctx, const Scene& scene);

/// Renders a scene of an explicit volume (not from the scene's source).
Image renderVolume(const gpu::Context& ctx, const Scene& scene, const Volume& volume);

/// Largest absolute per-channel difference, and the root mean square one.
struct ImageDiff {
    float maxAbs = 0.0f;
    double rms = 0.0;
    double meanAbs = 0.0;
};
ImageDiff compareImages(const Image& a, const Image& b);

} // namespace cutaway::test
