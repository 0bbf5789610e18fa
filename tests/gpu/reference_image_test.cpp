// Reference images: a fixed scene rendered and compared with a stored EXR.
// Tolerance: RMS difference <= 0.004 and largest difference <= 0.06 per
// channel (values in [0, 1]); loose enough for another driver's filtering
// precision, tight enough to catch a changed transfer function, light, camera
// or compositing rule.
//
// To regenerate after an intended change, look at the new image first, then:
//   CUTAWAY_UPDATE_REFERENCES=1 build/tests/test_gpu --gtest_filter='*Reference*'
#include "gpu_fixture.hpp"
#include "io/exr.hpp"
#include "io/png.hpp"

#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

const std::filesystem::path kReferenceDir =
    std::filesystem::path(CUTAWAY_SOURCE_DIR) / "tests" / "gpu" / "reference";

void checkAgainstReference(const Image& img, const std::string& name) {
    const auto path = kReferenceDir / (name + ".exr");
    if (std::getenv("CUTAWAY_UPDATE_REFERENCES")) {
        ExrOptions options;
        options.halfFloat = false;
        writeExr(path, img, options);
        writePng(kReferenceDir / (name + ".png"), img);
        GTEST_SKIP() << "reference written: " << path;
    }
    ASSERT_TRUE(std::filesystem::exists(path)) << "missing reference " << path;
    Image reference = readExr(path);
    ImageDiff d = compareImages(img, reference);
    EXPECT_LE(d.rms, 0.004) << name << ": max " << d.maxAbs;
    EXPECT_LE(d.maxAbs, 0.06f) << name << ": rms " << d.rms;
}

} // namespace

TEST_F(GpuTest, HeadPhantomMatchesReferenceImage) {
    Scene scene = headScene(64, 64, 64);
    scene.camera.azimuthDeg = 30.0;
    scene.camera.elevationDeg = 20.0;
    scene.lights.directional = {{glm::dvec3(-1.0, 1.0, -1.0), glm::vec3(1.0f, 0.9f, 0.8f), 0.4f}};
    scene.render.background = glm::vec4(0.1f, 0.1f, 0.12f, 1.0f);
    checkAgainstReference(renderScene(ctx(), scene), "head_phantom_64");
}

TEST_F(GpuTest, OrangePhantomOrthographicPostClassifiedMatchesReferenceImage) {
    Scene scene = headScene(64, 64, 48);
    scene.volume.phantom = "orange";
    scene.transfer.points = {{0.0, {0, 0, 0}, 0.0f},
                             {70.0, {0.95f, 0.95f, 0.85f}, 0.0f},
                             {90.0, {0.95f, 0.95f, 0.85f}, 0.1f},
                             {140.0, {1.0f, 0.5f, 0.05f}, 0.3f},
                             {200.0, {1.0f, 0.35f, 0.05f}, 0.6f}};
    scene.camera.projection = Projection::Orthographic;
    scene.camera.azimuthDeg = -40.0;
    scene.camera.elevationDeg = 35.0;
    scene.render.classification = Classification::Post;
    scene.render.sliceSpacing = 0.5;
    checkAgainstReference(renderScene(ctx(), scene), "orange_phantom_ortho_post");
}

} // namespace cutaway::test
