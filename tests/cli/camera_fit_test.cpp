// /camera/fit through the binary, on a peel whose flap leaves the volume's
// box and, lifted to 150 degrees, the view that fits the volume alone:
// "volume" cuts the flap at the image's edge, "deformed" frames it whole, and
// "sequence" holds one view over an animation that lifts it (the part of the
// head the flap never reaches is the same pixels in every frame).
#include "cli_util.hpp"
#include "io/exr.hpp"

#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

class CameraFit : public CliTest {
protected:
    fs::path scene(const std::string& fit, const std::string& animation = "") {
        return write(fit + ".json", R"({"version": 1,
            "volume": {"phantom": "head", "size": [32, 32, 32]},
            "camera": {"fit": ")" + fit +
                                        R"(", "orbit": {"azimuth": 0, "elevation": 0}},
            "operators": [{"type": "peeler",
                           "placement": {"translate": [0, 0, 10], "scale": [32, 32, 12]},
                           "params": {"hinge": -14, "thickness": 5, "angle": 150, "radius": 2}}],
            "render": {"size": [64, 64], "background": "transparent"})" +
                                        animation + "}");
    }

    Image render(const fs::path& s, const std::string& name, int frame = 0) {
        const CommandResult r =
            runCutaway("render " + s.string() + " -o " + (m_dir / (name + "_#.exr")).string());
        EXPECT_EQ(r.code, 0) << r.output;
        return readExr(m_dir / (name + "_" + std::to_string(frame) + ".exr"));
    }
};

// The largest alpha on the image's border rows and columns.
float borderAlpha(const Image& image) {
    float most = 0.0f;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (x == 0 || y == 0 || x == image.width - 1 || y == image.height - 1)
                most = std::max(most, image.rgba[4 * std::size_t(y * image.width + x) + 3]);
    return most;
}

TEST_F(CameraFit, DeformedFramesTheLiftedFlapThatVolumeCuts) {
    const Image volume = render(scene("volume"), "v");
    const Image deformed = render(scene("deformed"), "d");
    EXPECT_GT(borderAlpha(volume), 0.05f) << "the flap leaves the picture";
    EXPECT_EQ(borderAlpha(deformed), 0.0f) << "the flap is in the picture";
    float sum = 0.0f;
    for (std::size_t i = 3; i < deformed.rgba.size(); i += 4)
        sum += deformed.rgba[i];
    EXPECT_GT(sum, 50.0f) << "something shows";
}

// The bottom half of the image: the chin, far from the peel.
bool sameBottom(const Image& a, const Image& b) {
    const std::size_t half = a.rgba.size() / 2;
    return std::equal(a.rgba.begin() + std::ptrdiff_t(half), a.rgba.end(),
                      b.rgba.begin() + std::ptrdiff_t(half));
}

TEST_F(CameraFit, SequenceHoldsTheViewWhileTheFlapLifts) {
    const std::string lift = R"(, "animation": {"frames": [0, 2], "tracks": [
        {"target": "/operators/0/params/angle", "keys": [{"frame": 0, "value": 0},
                                                          {"frame": 2, "value": 150}]}]})";
    const fs::path sequence = scene("sequence", lift);
    const Image first = render(sequence, "s", 0);
    const Image last = readExr(m_dir / "s_2.exr");
    EXPECT_TRUE(sameBottom(first, last)) << "one view for every frame";
    EXPECT_EQ(borderAlpha(last), 0.0f) << "the lifted flap is in the picture";
    // Control: fitting each frame to itself moves the view as the flap lifts.
    const fs::path deformed = scene("deformed", lift);
    const Image dFirst = render(deformed, "d", 0);
    EXPECT_FALSE(sameBottom(dFirst, readExr(m_dir / "d_2.exr")));
}

} // namespace
} // namespace cutaway::test
