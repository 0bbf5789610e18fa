// `cutaway export -o x.nii.gz`: NIfTI-1 beside NRRD, read back by an
// independent reader, NiBabel (Debian's python3-nibabel, through the system
// interpreter): its voxels are the NRRD export's, and its affine the scan's
// geometry in RAS, on a scan whose index axes are oblique and mirrored.
#include "cli_util.hpp"
#include "volume/phantom.hpp"
#include "volume/volume.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

// Index axes turned 35 degrees about z, k reversed (det -1).
glm::dmat3 mirroredOblique() {
    const double c = std::cos(glm::radians(35.0)), s = std::sin(glm::radians(35.0));
    return glm::dmat3(glm::dvec3(c, s, 0), glm::dvec3(-s, c, 0), glm::dvec3(0, 0, -1));
}

class ExportNifti : public CliTest {
protected:
    void SetUp() override {
        CliTest::SetUp();
        Phantom p = makePhantom("head", {20, 18, 14}, {1.0, 1.25, 2.0});
        p.values.direction = mirroredOblique();
        p.values.origin = {-31.5, 87.25, -12.0};
        p.values.space = Space::LPS;
        writeNrrd(m_dir / "scan.nrrd", p.values);
        writeNrrd(m_dir / "labels.nrrd", p.labels);
        m_scene = write("scene.json", R"({"version": 1, "volume": {"file": "scan.nrrd"},
            "labels": {"file": "labels.nrrd"},
            "operators": [{"type": "retractor", "placement": {"translate": [0, 0, 9],
                           "scale": [10, 12, 10]}, "params": {"opening": 6}}]})");
    }

    CommandResult exportTo(const std::string& options) {
        return runCutaway("export " + m_scene.string() + " " + options);
    }

    // What NiBabel reads: shape, dtype, the affine (sform) and the qform's,
    // and the sum of the voxels' values (slope and intercept applied).
    nlohmann::json nibabel(const fs::path& file) {
        const fs::path script = write("read.py", R"(import json, sys
import nibabel
img = nibabel.load(sys.argv[1])
data = img.get_fdata()
print(json.dumps({"shape": list(img.shape), "dtype": str(img.get_data_dtype()),
    "affine": img.affine.tolist(), "qform": img.get_qform().tolist(),
    "codes": [int(img.header["sform_code"]), int(img.header["qform_code"])],
    "sum": float(data.sum())}))
)");
        const CommandResult r =
            runProgram("/usr/bin/python3", script.string() + " " + file.string());
        EXPECT_EQ(r.code, 0) << r.output;
        return nlohmann::json::parse(r.output, nullptr, false);
    }

    fs::path m_scene;
};

// The affine NIfTI must hold for `v`: RAS = diag(-1, -1, 1) (origin + D spacing i).
glm::dmat4 rasAffine(const Volume& v) {
    glm::dmat4 a(1.0);
    for (int c = 0; c < 3; ++c)
        a[c] = glm::dvec4(v.direction[c] * v.spacing[c], 0.0);
    a[3] = glm::dvec4(v.origin, 1.0);
    return glm::dmat4(glm::dvec4(-1, 0, 0, 0), glm::dvec4(0, -1, 0, 0), glm::dvec4(0, 0, 1, 0),
                      glm::dvec4(0, 0, 0, 1)) *
           a;
}

double worstAffineError(const nlohmann::json& rows, const glm::dmat4& expected) {
    double worst = 0.0;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            worst = std::max(worst, std::abs(rows[r][c].get<double>() - expected[c][r]));
    return worst;
}

double sumOf(const Volume& v) {
    double sum = 0.0;
    for (std::size_t i = 0; i < v.voxelCount(); ++i)
        sum += v.value(i);
    return sum;
}

TEST_F(ExportNifti, NiBabelReadsTheVoxelsAndTheAffine) {
    ASSERT_EQ(exportTo("-o " + (m_dir / "x.nrrd").string()).code, 0);
    const Volume reference = readVolume(m_dir / "x.nrrd");
    for (const char* name : {"x.nii.gz", "x.nii"}) {
        SCOPED_TRACE(name);
        const CommandResult r = exportTo("-o " + (m_dir / name).string());
        ASSERT_EQ(r.code, 0) << r.output;
        const nlohmann::json read = nibabel(m_dir / name);
        ASSERT_FALSE(read.is_discarded());
        EXPECT_EQ(read["shape"],
                  nlohmann::json::array({reference.dims.x, reference.dims.y, reference.dims.z}));
        EXPECT_EQ(read["dtype"], "uint8") << "the scan's own type: its values fit it";
        EXPECT_EQ(read["codes"], nlohmann::json::array({1, 1})) << "a NRRD scan: scanner";
        const glm::dmat4 expected = rasAffine(reference);
        EXPECT_LT(worstAffineError(read["affine"], expected), 1e-4) << read["affine"].dump();
        // The qform holds the same rotation, its mirror in qfac.
        EXPECT_LT(worstAffineError(read["qform"], expected), 1e-4) << read["qform"].dump();
        EXPECT_NEAR(read["sum"].get<double>(), sumOf(reference), 1e-6 * sumOf(reference));
        // Control: the LPS affine (the NRRD's) is not what NIfTI holds.
        glm::dmat4 lps = expected;
        lps[3] = glm::dvec4(reference.origin, 1.0);
        EXPECT_GT(worstAffineError(read["affine"], lps), 1.0);
        // cutaway's own reader gives the NRRD's voxels and geometry back.
        const Volume back = readVolume(m_dir / name);
        EXPECT_EQ(back.data, reference.data);
        EXPECT_LT(glm::length(back.origin - reference.origin), 1e-4);
    }
}

TEST_F(ExportNifti, TheLabelsExportAsIntegersAndNamesAreChecked) {
    const CommandResult r = exportTo("-o " + (m_dir / "x.nii.gz").string() + " --labels-output " +
                                     (m_dir / "l.nii.gz").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json read = nibabel(m_dir / "l.nii.gz");
    EXPECT_EQ(read["dtype"], "uint8");
    EXPECT_GT(read["sum"].get<double>(), 0.0);
    // A gzip name with --raw, and a name of no format: refused, nothing written.
    const std::string o = "-o " + m_dir.string();
    for (const char* bad : {"/y.nii.gz --raw", "/y.nifti"}) {
        const CommandResult e = exportTo(o + bad);
        EXPECT_EQ(e.code, 2) << e.output;
        EXPECT_NE(e.output.find("-o " + m_dir.string()), std::string::npos) << e.output;
    }
    EXPECT_FALSE(fs::exists(m_dir / "y.nii.gz"));
    EXPECT_FALSE(fs::exists(m_dir / "y.nifti"));
}

// The export keeps the scan's identity: a NIfTI scan with sform code 4
// (MNI) and qform code 2 (aligned), int16 with a slope and intercept, comes
// back with those codes and as int16 with its scaling (it came back as
// codes 1 and float32). --type chooses; a type the values do not fit is
// refused, nothing written. Control: --type float32 gives float32, and a
// scaled scan written as NRRD (no standard scaling) is float32.
TEST_F(ExportNifti, TheExportKeepsTheScansCodesAndType) {
    const fs::path script = write("make.py", R"(import sys
import numpy, nibabel
data = (numpy.arange(20 * 18 * 14) % 200).reshape((20, 18, 14), order="F").astype(numpy.int16)
affine = numpy.diag([1.0, 1.25, 2.0, 1.0])
img = nibabel.Nifti1Image(data, affine)
img.header.set_sform(affine, code=4)
img.header.set_qform(affine, code=2)
img.header.set_slope_inter(2.0, -1024.0)
nibabel.save(img, sys.argv[1])
)");
    ASSERT_EQ(
        runProgram("/usr/bin/python3", script.string() + " " + (m_dir / "mni.nii.gz").string())
            .code,
        0);
    const fs::path scene = write("mni.json", R"({"version": 1, "volume": {"file": "mni.nii.gz"},
        "operators": [{"type": "peeler", "placement": {"translate": [0, 0, 9],
                       "scale": [10, 12, 10]}}]})");
    const auto exportMni = [&](const std::string& options) {
        return runCutaway("export " + scene.string() + " " + options);
    };
    ASSERT_EQ(exportMni("-o " + (m_dir / "a.nii.gz").string()).code, 0);
    nlohmann::json read = nibabel(m_dir / "a.nii.gz");
    EXPECT_EQ(read["codes"], nlohmann::json::array({4, 2}));
    EXPECT_EQ(read["dtype"], "int16");
    const Volume a = readVolume(m_dir / "a.nii.gz");
    EXPECT_EQ(a.slope, 2.0);
    EXPECT_EQ(a.inter, -1024.0);

    ASSERT_EQ(exportMni("-o " + (m_dir / "f.nii.gz").string() + " --type float32").code, 0);
    read = nibabel(m_dir / "f.nii.gz");
    EXPECT_EQ(read["dtype"], "float32") << "control";
    EXPECT_EQ(read["codes"], nlohmann::json::array({4, 2}));
    ASSERT_EQ(exportMni("-o " + (m_dir / "n.nrrd").string()).code, 0);
    EXPECT_EQ(readVolume(m_dir / "n.nrrd").type, VoxelType::F32) << "NRRD has no scaling";

    // Raw numbers 0..199 (values -1024..-626): int8 cannot hold them.
    const CommandResult refused = exportMni("-o " + (m_dir / "u.nii.gz").string() + " --type int8");
    EXPECT_EQ(refused.code, 2) << refused.output;
    EXPECT_NE(refused.output.find("--type int8: the deformed volume holds values"),
              std::string::npos)
        << refused.output;
    EXPECT_FALSE(fs::exists(m_dir / "u.nii.gz"));
}

} // namespace
} // namespace cutaway::test
