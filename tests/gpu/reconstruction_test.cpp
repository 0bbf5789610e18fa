// Reconstruction: how close a render of a coarse grid comes to the object it
// samples, against references that today's reconstruction cannot move:
// renders of the same analytic object (smooth_objects.hpp) on a 0.25 mm
// grid, and of the demo's head phantom at twice the resolution, kept in
// tests/gpu/reference/ as half-float EXR files (0.05 % of a value, far below
// the figures read here). The figures are docs/quality.md's measure (display
// encoded, gamma 2.2) over the opaque surface less 2 pixels at its edges,
// where the silhouette of a coarser grid may fall a pixel apart; for the
// demo's translucent head, over the whole picture.
//
// Sampling is fine and the same in millimetres for every grid (a sample
// every 0.25 mm, opacity per millimetre), so only the reconstruction
// differs. The bounds hold the figures measured on lavapipe less 1 dB at
// most (docs/quality.md): the gradient before Farid and Simoncelli's pair,
// Sobel's, fails those of the 1 mm and 1.5 mm grids (49.3 and 46.3 dB); the
// controls show that the measure sees terraces and lost detail.
//
// To regenerate the references after an intended change to them (not to
// the reconstruction, which they must hold still), look at them first, then:
//   CUTAWAY_UPDATE_REFERENCES=1 build/tests/test_gpu --gtest_filter='Reconstruction*'
#include "gpu_fixture.hpp"
#include "io/exr.hpp"
#include "io/picture_difference.hpp"
#include "io/png.hpp"
#include "smooth_objects.hpp"
#include "volume/phantom.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <gtest/gtest.h>
#include <string>

namespace cutaway::test {
namespace {

const std::filesystem::path kReconstructionReferences =
    std::filesystem::path(CUTAWAY_SOURCE_DIR) / "tests" / "gpu" / "reference";
constexpr int kReconstructionSize = 128;
constexpr int kSurfaceErode = 2;

class Reconstruction : public GpuTest {
protected:
    /// The stored reference `name`, or, with CUTAWAY_UPDATE_REFERENCES set,
    /// `render()`'s picture written as it.
    Image reference(const std::string& name, const std::function<Image()>& render) {
        const std::filesystem::path path = kReconstructionReferences / (name + ".exr");
        if (std::getenv("CUTAWAY_UPDATE_REFERENCES")) {
            const Image image = render();
            writeExr(path, image, ExrOptions{});
            writePng(kReconstructionReferences / (name + ".png"), image);
            return image;
        }
        EXPECT_TRUE(std::filesystem::exists(path)) << "missing reference " << path;
        return readExr(path);
    }

    Image renderObject(SmoothObject object, glm::dvec3 spacing, RenderMethod method,
                       double stepMm = 0.25, Filter filter = Filter::Linear) {
        Scene scene = smoothObjectScene(kReconstructionSize, method);
        scene.render.filter = filter;
        scene.render.sliceSpacing = stepMm / std::min({spacing.x, spacing.y, spacing.z});
        return renderVolume(ctx(), scene, sampleSmoothObject(object, spacing));
    }

    Image objectReference(SmoothObject object, const std::string& name) {
        return reference("smooth_" + name, [&] {
            return renderObject(object, glm::dvec3(0.25), RenderMethod::Slicing, 0.125);
        });
    }
};

const char* methodName(RenderMethod method) {
    return method == RenderMethod::Slicing ? "slicing" : "raycast";
}

PictureDifference onSurface(const Image& image, const Image& reference) {
    const std::vector<bool> mask = opaqueInterior(reference, kSurfaceErode);
    const PictureDifference d = comparePictures(image, reference, mask);
    EXPECT_GT(d.pixels, std::size_t(kReconstructionSize * kReconstructionSize / 5))
        << "the surface must fill the view";
    return d;
}

struct Grid {
    glm::dvec3 spacing;
    const char* name;
    double floorDb; // the figure measured on lavapipe, less 1 dB at most
};

TEST_F(Reconstruction, AnEllipsoidOnThickSlices) {
    const Image truth = objectReference(SmoothObject::Ellipsoid, "ellipsoid");
    for (RenderMethod method : {RenderMethod::Slicing, RenderMethod::Raycast}) {
        double thin = 0.0, thick = 0.0;
        for (const Grid& grid :
             {Grid{{1.0, 1.0, 1.0}, "1 mm", 50.6}, Grid{{1.0, 1.0, 1.5}, "1 x 1 x 1.5 mm", 46.4},
              Grid{{1.0, 1.0, 3.0}, "1 x 1 x 3 mm", 33.8}}) {
            const PictureDifference d =
                onSurface(renderObject(SmoothObject::Ellipsoid, grid.spacing, method), truth);
            std::printf("ellipsoid, %s, %s: %.2f dB, %.2f %% of pixels off\n", methodName(method),
                        grid.name, d.psnr, 100.0 * d.shareOff);
            EXPECT_GT(d.psnr, grid.floorDb) << methodName(method) << " " << grid.name;
            (grid.spacing.z == 1.0 ? thin : thick) = d.psnr;
        }
        // Control: the measure sees the terraces of 3 mm slices.
        EXPECT_LT(thick, thin - 5.0) << methodName(method);
    }
}

TEST_F(Reconstruction, TheBumpsOfABumpyEllipsoid) {
    const Image truth = objectReference(SmoothObject::Bumpy, "bumpy");
    const Image smooth = objectReference(SmoothObject::Ellipsoid, "ellipsoid");
    for (RenderMethod method : {RenderMethod::Slicing, RenderMethod::Raycast}) {
        for (const Grid& grid :
             {Grid{{1.0, 1.0, 1.0}, "1 mm", 31.4}, Grid{{1.0, 1.0, 3.0}, "1 x 1 x 3 mm", 25.4}}) {
            const PictureDifference d =
                onSurface(renderObject(SmoothObject::Bumpy, grid.spacing, method), truth);
            std::printf("bumpy ellipsoid, %s, %s: %.2f dB, %.2f %% of pixels off\n",
                        methodName(method), grid.name, d.psnr, 100.0 * d.shareOff);
            EXPECT_GT(d.psnr, grid.floorDb) << methodName(method) << " " << grid.name;
        }
    }
    // Control: the bumps are detail the measure sees; the smooth ellipsoid,
    // a blur that lost them, is far from the bumpy one.
    const PictureDifference blurred = onSurface(smooth, truth);
    std::printf("smooth against bumpy ellipsoid: %.2f dB\n", blurred.psnr);
    EXPECT_LT(blurred.psnr, 27.0);
}

// /render/filter "cubic" on the same grids, slicing (the ray caster takes
// the same samples: cubic_filter_render_test.cpp). Measured on lavapipe:
// 46.6, 43.6 and 33.5 dB for the ellipsoid (below linear filtering on every
// grid), 33.8 and 26.5 dB for the bumps (a little above); bounds 1 dB less.
TEST_F(Reconstruction, TheCubicFilterOnTheSameGrids) {
    const Image smooth = objectReference(SmoothObject::Ellipsoid, "ellipsoid");
    const Image bumpy = objectReference(SmoothObject::Bumpy, "bumpy");
    struct Case {
        SmoothObject object;
        Grid grid;
        const Image* truth;
    };
    for (const Case& c :
         {Case{SmoothObject::Ellipsoid, {{1.0, 1.0, 1.0}, "1 mm", 45.6}, &smooth},
          Case{SmoothObject::Ellipsoid, {{1.0, 1.0, 1.5}, "1 x 1 x 1.5 mm", 42.5}, &smooth},
          Case{SmoothObject::Ellipsoid, {{1.0, 1.0, 3.0}, "1 x 1 x 3 mm", 32.4}, &smooth},
          Case{SmoothObject::Bumpy, {{1.0, 1.0, 1.0}, "1 mm", 32.7}, &bumpy},
          Case{SmoothObject::Bumpy, {{1.0, 1.0, 3.0}, "1 x 1 x 3 mm", 25.5}, &bumpy}}) {
        const char* name = c.object == SmoothObject::Bumpy ? "bumpy ellipsoid" : "ellipsoid";
        const PictureDifference cubic = onSurface(
            renderObject(c.object, c.grid.spacing, RenderMethod::Slicing, 0.25, Filter::Cubic),
            *c.truth);
        std::printf("%s, %s, cubic: %.2f dB, %.2f %% of pixels off\n", name, c.grid.name,
                    cubic.psnr, 100.0 * cubic.shareOff);
        EXPECT_GT(cubic.psnr, c.grid.floorDb) << name << " " << c.grid.name;
    }
}

TEST_F(Reconstruction, TheDemoPhantomAgainstItselfAtTwiceTheResolution) {
    // The demo's head, transfer function, lights and view direction without
    // its flap, framed to fill the picture, on an 80^3 grid (2 mm) against
    // the same 160 mm box on a 160^3 grid.
    Scene scene = loadScene(std::filesystem::path(CUTAWAY_SOURCE_DIR) / "scenes" / "demo.json");
    scene.operators.clear();
    scene.camera.distance = 0.0;
    scene.camera.zoom = 1.6;
    scene.render.width = scene.render.height = kReconstructionSize;
    scene.render.jitter = false;
    scene.render.samples = 1;
    scene.unitDistance = 1.0;
    auto render = [&](int size, double stepMm, RenderMethod method) {
        Scene s = scene;
        const double spacing = 160.0 / size;
        s.render.method = method;
        s.render.sliceSpacing = stepMm / spacing;
        return renderVolume(ctx(), s,
                            makePhantom("head", glm::ivec3(size), glm::dvec3(spacing)).values);
    };
    const Image truth =
        reference("demo_head_160", [&] { return render(160, 0.25, RenderMethod::Slicing); });
    for (RenderMethod method : {RenderMethod::Slicing, RenderMethod::Raycast}) {
        const Image coarse = render(80, 0.5, method);
        const PictureDifference whole = comparePictures(coarse, truth);
        std::printf("demo head at 2 mm against 1 mm, %s: %.2f dB, %.2f %% of pixels off\n",
                    methodName(method), whole.psnr, 100.0 * whole.shareOff);
        EXPECT_GT(whole.psnr, 42.8) << methodName(method);
    }
    // Control: the 1 mm grid rendered now is the reference, so what the
    // figures see is the coarser grid's.
    EXPECT_GT(comparePictures(render(160, 0.25, RenderMethod::Slicing), truth).psnr, 60.0);
}

} // namespace
} // namespace cutaway::test
