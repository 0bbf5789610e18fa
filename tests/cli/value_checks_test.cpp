// What a scene's values do on a scan, through the binary: a transfer
// function copied in 0..1 onto Hounsfield units, or visible only where the
// scan has no values, is warned of; a soft-tissue window keeps air
// transparent (voxels below it are drawn as the scan's lowest value, not as
// the window's bottom), and voxels it still changes are counted in a warning;
// validate notes the value range and Otsu's threshold even off a terminal.
#include "cli_util.hpp"
#include "io/exr.hpp"
#include "volume/phantom.hpp"
#include "volume/volume.hpp"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

class ValueChecks : public CliTest {
protected:
    // The head phantom in Hounsfield-like units: 10 v - 1000 (air -1000).
    void SetUp() override {
        CliTest::SetUp();
        const Volume head = makePhantom("head", {32, 32, 32}).values;
        Volume hu = Volume::allocate(head.dims, VoxelType::I16, head.spacing);
        for (std::size_t i = 0; i < head.voxelCount(); ++i) {
            const auto v = static_cast<std::int16_t>(std::lround(10.0 * head.value(i) - 1000.0));
            std::memcpy(hu.data.data() + 2 * i, &v, 2);
        }
        writeNrrd(m_dir / "hu.nrrd", hu);
    }

    fs::path scene(const std::string& name, const std::string& points,
                   const std::string& window = "", const std::string& extra = "") {
        return write(name, R"({"version": 1, "volume": {"file": "hu.nrrd")" + window + R"(},
            "transfer": {"points": [)" +
                               points + R"(]},
            "render": {"size": [32, 32], "background": "transparent"})" +
                               extra + "}");
    }

    CommandResult validate(const fs::path& s) { return runCutaway("validate " + s.string()); }
    Image render(const fs::path& s, const std::string& name) {
        const CommandResult r =
            runCutaway("render " + s.string() + " -o " + (m_dir / (name + "_#.exr")).string());
        EXPECT_EQ(r.code, 0) << r.output;
        return readExr(m_dir / (name + "_0.exr"));
    }
};

constexpr const char* kNormalized =
    R"({"value": 0.1, "color": [1, 1, 1], "alpha": 0}, {"value": 1, "color": [1, 1, 1], "alpha": 1})";
constexpr const char* kSoftTissue = R"({"value": -1000, "color": [1, 0.8, 0.7], "alpha": 0},
    {"value": -200, "color": [1, 0.8, 0.7], "alpha": 0.3}, {"value": 400, "color": [1, 1, 1], "alpha": 1})";

TEST_F(ValueChecks, ATransferFunctionInOtherUnitsIsWarnedOf) {
    for (const char* command : {"validate ", "render "}) {
        const CommandResult r = runCutaway(command + scene("n.json", kNormalized).string() +
                                           " -o " + (m_dir / "n_#.exr").string());
        EXPECT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("warning: " + (m_dir / "n.json").string() +
                                ": /transfer/points: the transfer function's points lie in "
                                "[0.1, 1], and the volume's values span [-1000, 1220]"),
                  std::string::npos)
            << command << r.output;
    }
    const CommandResult outside = validate(scene(
        "o.json",
        R"({"value": 5000, "color": [1, 1, 1], "alpha": 0}, {"value": 6000, "color": [1, 1, 1], "alpha": 1},
           {"value": 7000, "color": [1, 1, 1], "alpha": 0})"));
    EXPECT_NE(outside.output.find("/transfer/points: the transfer function is visible only in "
                                  "[5000, 7000], and the volume's values span [-1000, 1220]: "
                                  "nothing shows"),
              std::string::npos)
        << outside.output;
    // Control: a function in the scan's units.
    const CommandResult fine = validate(scene("f.json", kSoftTissue));
    EXPECT_EQ(fine.code, 0) << fine.output;
    EXPECT_EQ(fine.output.find("warning"), std::string::npos) << fine.output;
}

// The share of pixels that show something (alpha above 0.02).
double coverage(const Image& image) {
    std::size_t shown = 0;
    for (std::size_t i = 3; i < image.rgba.size(); i += 4)
        shown += image.rgba[i] > 0.02f ? 1 : 0;
    return double(shown) / double(image.rgba.size() / 4);
}

// A window over soft tissue: the air below it stays air. Against the same
// scene without a window, the picture covers the same pixels to 5 % of the
// image (measured 3.5 %: the function's ramp from -1000 to -200 lies below
// the window, so the translucent halo of values there is drawn as air, which
// the warning counts), where air drawn visible covers the whole box.
TEST_F(ValueChecks, AWindowKeepsTheValuesBelowItAsTheScanHasThem) {
    const fs::path windowedScene = scene("w.json", kSoftTissue, R"(, "window": [-200, 400])");
    const Image windowed = render(windowedScene, "w");
    const Image whole = render(scene("a.json", kSoftTissue), "a");
    EXPECT_NEAR(coverage(windowed), coverage(whole), 0.05);
    EXPECT_NE(validate(windowedScene).output.find("lie outside [-200, 400]"), std::string::npos);
    EXPECT_GT(coverage(whole), 0.1) << "the head shows";
    // Control: air made visible, as a window's bottom drawn for it was.
    const Image foggy =
        render(scene("c.json", R"({"value": -1000, "color": [1, 1, 1], "alpha": 0.3},
        {"value": -200, "color": [1, 0.8, 0.7], "alpha": 0.3}, {"value": 400, "color": [1, 1, 1], "alpha": 1})",
                     R"(, "window": [-200, 400])"),
               "c");
    EXPECT_GT(coverage(foggy), coverage(whole) + 0.1);
}

// A visible band below the window (lung, say): its voxels are drawn as air.
TEST_F(ValueChecks, VoxelsTheWindowStillHidesAreCounted) {
    const std::string band = R"({"value": -900, "color": [1, 1, 1], "alpha": 0},
        {"value": -700, "color": [1, 1, 1], "alpha": 0.5}, {"value": -500, "color": [1, 1, 1], "alpha": 0},
        {"value": 400, "color": [1, 1, 1], "alpha": 1})";
    const CommandResult r = validate(scene("b.json", band, R"(, "window": [-200, 400])"));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("/volume/window: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("lie outside [-200, 400] where /transfer shows some values and not "
                            "others"),
              std::string::npos)
        << r.output;
    // Control: the window that holds the band.
    const CommandResult wide = validate(scene("wide.json", band, R"(, "window": [-1000, 400])"));
    EXPECT_EQ(wide.output.find("lie outside"), std::string::npos) << wide.output;
}

TEST_F(ValueChecks, ValidateNotesWhatItDerivesOffATerminal) {
    const CommandResult r = validate(scene("s.json", kSoftTissue, "", R"(,
        "operators": [{"type": "peeler", "placement": {"translate": [0, 0, 10], "scale": [20, 20, 12]},
                       "alignment": {"mode": "surface"}}])"));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("note: " + (m_dir / "s.json").string() +
                            ": the volume's values span [-1000, 1220]"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("/operators/0/alignment/threshold: Otsu's threshold of the volume is "),
              std::string::npos)
        << r.output;
    const CommandResult quiet = runCutaway("validate -q " + (m_dir / "s.json").string());
    EXPECT_EQ(quiet.output.find("note:"), std::string::npos) << quiet.output;
}

} // namespace
} // namespace cutaway::test
