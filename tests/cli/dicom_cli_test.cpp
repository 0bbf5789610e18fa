// DICOM through the binary: `cutaway info` lists a folder's series, a scene
// picks one with /volume/series, and scenes/dicom_ct_head.json renders the
// series scripts/write_dicom.py writes from ../shared/data as the scan does.
#include "cli_util.hpp"
#include "io/exr.hpp"

#include <cstdlib>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

class DicomCli : public CliTest {
protected:
    // A small series from the head phantom's NRRD (written by the binary).
    fs::path series(const std::string& folder, const std::string& options) {
        const fs::path nrrd = m_dir / "phantom.nrrd";
        if (!fs::exists(nrrd)) {
            const fs::path scene = write("p.json", R"({"version": 1,
                "volume": {"phantom": "head", "size": [16, 16, 12]}})");
            const CommandResult r = runCutaway("export " + scene.string() + " -o " + nrrd.string());
            EXPECT_EQ(r.code, 0) << r.output;
        }
        return writeSeries(nrrd, m_dir / folder, options);
    }
    static fs::path writeSeries(const fs::path& in, const fs::path& out,
                                const std::string& options) {
        const std::string command = "/usr/bin/python3 " + std::string(CUTAWAY_SOURCE_DIR) +
                                    "/scripts/write_dicom.py " + in.string() + " " + out.string() +
                                    " " + options + " > /dev/null";
        EXPECT_EQ(std::system(command.c_str()), 0) << command;
        return out;
    }
};

TEST_F(DicomCli, InfoListsEachSeriesAndDescribesThePickedOne) {
    series("study/a", "--series-number 2 --description 'CT head'");
    series("study/b", "--series-number 9 --description Localizer");
    const std::string study = (m_dir / "study").string();
    const CommandResult list = runCutaway("info " + study);
    EXPECT_EQ(list.code, 0) << list.output;
    EXPECT_NE(list.output.find("series 2  \"CT head\"  CT  16 x 16 x 12  12 file(s)"),
              std::string::npos)
        << list.output;
    EXPECT_NE(list.output.find("series 9  \"Localizer\""), std::string::npos) << list.output;
    EXPECT_EQ(list.output.find("dims"), std::string::npos) << "no series picked: none described";
    const CommandResult one = runCutaway("info " + study + " --series localizer");
    EXPECT_EQ(one.code, 0) << one.output;
    EXPECT_NE(one.output.find("dims     16 x 16 x 12"), std::string::npos) << one.output;
    EXPECT_NE(one.output.find("space    LPS"), std::string::npos) << one.output;
}

// /volume/series picks a series; without it a folder of two is exit 2
// listing them; a series no DICOM path allows is refused at its pointer.
TEST_F(DicomCli, ASceneReadsTheSeriesItNames) {
    series("study/a", "--series-number 2 --description 'CT head'");
    series("study/b", "--series-number 9 --description Localizer --oblique 20");
    const auto scene = [&](const std::string& volume) {
        return write("s.json", R"({"version": 1, "volume": )" + volume +
                                   R"(, "render": {"size": [24, 24]}})");
    };
    const fs::path picked = scene(R"({"file": "study", "series": 2})");
    CommandResult r =
        runCutaway("render " + picked.string() + " -o " + (m_dir / "a_#.exr").string());
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readExr(m_dir / "a_0.exr").width, 24);
    r = runCutaway("validate " + scene(R"({"file": "study"})").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("holds 2 series"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\"Localizer\""), std::string::npos) << r.output;
    r = runCutaway("validate " + scene(R"({"phantom": "head", "series": 2})").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("/volume/series"), std::string::npos) << r.output;
    r = runCutaway("validate " + scene(R"({"file": "study", "series": 7})").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("no series matches \"7\""), std::string::npos) << r.output;
}

// A series with a slice cut short in its header: `info`, `validate` and
// `render` each end with exit 2 and a message naming the slice (GDCM's
// assertion on it ends a child process, not cutaway), and nothing is written.
// A series folder holding links to its parent and to itself is read once, in
// the time it takes (a walk that follows them never ends).
TEST_F(DicomCli, ACutSliceIsAnErrorAndLinksDoNotLoop) {
    const fs::path folder = series("cut", "");
    fs::resize_file(folder / "slice0005.dcm", 132); // its preamble and "DICM" alone
    const fs::path scene = write("s.json", R"({"version": 1, "volume": {"file": "cut"},
        "render": {"size": [24, 24]}})");
    const fs::path exr = m_dir / "f_#.exr";
    for (const std::string& command : {"info " + folder.string(), "validate " + scene.string(),
                                       "render " + scene.string() + " -o " + exr.string()}) {
        SCOPED_TRACE(command);
        const CommandResult r = runCutaway(command);
        EXPECT_EQ(r.code, 2) << r.output;
        EXPECT_NE(r.output.find("slice0005.dcm: a damaged or truncated DICOM file"),
                  std::string::npos)
            << r.output;
    }
    EXPECT_FALSE(fs::exists(m_dir / "f_0.exr")) << "nothing is written";
    // GDCM's own messages: hidden, shown escaped after "cutaway: GDCM: "
    // with --verbose.
    EXPECT_EQ(runCutaway("info " + folder.string()).output.find("cutaway: GDCM: "),
              std::string::npos);
    const CommandResult verbose = runCutaway("info --verbose " + folder.string());
    EXPECT_EQ(verbose.code, 2);
    EXPECT_NE(verbose.output.find("cutaway: GDCM: "), std::string::npos) << verbose.output;

    const fs::path loops = series("loops", "");
    fs::create_directory_symlink("..", loops / "up");
    fs::create_directory_symlink(".", loops / "self");
    const CommandResult r = runCutaway("info " + loops.string());
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("16 x 16 x 12  12 file(s)"), std::string::npos) << r.output;
}

// The example scene on the series written from ct_head renders as the
// same scene on the scan itself (the same values and index grid): the
// EXRs agree to 1e-3 (measured: identical).
TEST_F(DicomCli, TheExampleSceneRendersAsItsScan) {
    const fs::path scan = fs::path(CUTAWAY_SHARED_DATA) / "ct_head.nii.gz";
    if (!fs::exists(scan)) GTEST_SKIP() << scan << " not found: the shared scans are absent";
    const fs::path folder = writeSeries(scan, m_dir / "ct_head", "--description 'CT head'");
    const std::string scenes = std::string(CUTAWAY_SOURCE_DIR) + "/scenes/";
    const std::string small = " --size 48x48 --set /operators=[] -o ";
    CommandResult r = runCutaway("render " + scenes + "dicom_ct_head.json --set '/volume/file=\"" +
                                 folder.string() + "\"'" + small + (m_dir / "d_#.exr").string());
    ASSERT_EQ(r.code, 0) << r.output;
    r = runCutaway("render " + scenes + "fig3_surface_ct_head.json" + small +
                   (m_dir / "n_#.exr").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const Image a = readExr(m_dir / "d_0.exr"), b = readExr(m_dir / "n_0.exr");
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    float worst = 0.0f, sum = 0.0f;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) {
        worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]));
        sum += b.rgba[i];
    }
    EXPECT_LT(worst, 1e-3f);
    EXPECT_GT(sum, 10.0f) << "control: the picture is not empty";
}

} // namespace
} // namespace cutaway::test
