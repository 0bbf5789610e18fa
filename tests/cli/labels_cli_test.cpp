// Label volumes through the binary: a label file that does not fit the scan
// is bad input (exit 2) naming the file, before anything is written; labels
// with ids beyond 255 classify by label and align a segment; the feature
// bakes are recorded in the EXR header.
#include "cli_util.hpp"
#include "io/exr.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"
#include "volume/phantom.hpp"
#include "volume/volume.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <gtest/gtest.h>
#include <string>

namespace fs = std::filesystem;

namespace cutaway::test {
namespace {

constexpr int kScanSide = 24;

/// A label volume of `type` whose voxel (x, y, z) holds id(x, y, z).
Volume labelVolume(glm::ivec3 dims, VoxelType type, glm::dvec3 spacing,
                   const std::function<double(int, int, int)>& id) {
    Volume v = Volume::allocate(dims, type, spacing);
    const std::size_t size = voxelSize(type);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                std::byte* at = v.data.data() + v.index(x, y, z) * size;
                const double value = id(x, y, z);
                if (type == VoxelType::I16) {
                    const auto s = static_cast<std::int16_t>(value);
                    std::memcpy(at, &s, sizeof s);
                } else if (type == VoxelType::F32) {
                    const auto f = static_cast<float>(value);
                    std::memcpy(at, &f, sizeof f);
                } else {
                    ADD_FAILURE() << "labelVolume: unhandled type";
                }
            }
    return v;
}

/// 2000 in a ball of radius 6 voxels about the centre, 1000 around it.
double shellAndCore(int x, int y, int z) {
    const double c = 0.5 * (kScanSide - 1);
    const double dx = x - c, dy = y - c, dz = z - c;
    return dx * dx + dy * dy + dz * dz <= 36.0 ? 2000.0 : 1000.0;
}

class LabelsCli : public CliTest {
protected:
    /// The head phantom's values as scan.nrrd (24^3 voxels, 1 mm).
    fs::path writeScan() {
        const Phantom p = makePhantom("head", glm::ivec3(kScanSide));
        const fs::path path = m_dir / "scan.nrrd";
        writeNrrd(path, p.values);
        return path;
    }
    fs::path writeLabels(const Volume& labels) {
        const fs::path path = m_dir / "labels.nrrd";
        writeNrrd(path, labels);
        return path;
    }
    /// A scene on scan.nrrd and labels.nrrd with a segment-aligned peeler on
    /// label 2000 ("core") and `extra` (more top-level keys, each followed by a comma).
    fs::path writeScene(const std::string& extra = "") {
        return write("scene.json", R"({
          "version": 1,
          "volume": { "file": "scan.nrrd" },
          "labels": { "file": "labels.nrrd", "names": { "shell": 1000, "core": 2000 } },
          )" + extra + R"(
          "operators": [ { "type": "peeler",
            "placement": { "translate": [0, 0, 6], "scale": [20, 20, 12] },
            "resolution": 16,
            "alignment": { "mode": "segment", "labels": ["core"], "band": 2 } } ],
          "render": { "size": [48, 48] },
          "output": { "pattern": "frames/labels_####.exr" }
        })");
    }
    CommandResult render(const fs::path& scene) {
        return runCutaway("render " + scene.string() + " --size 48x48");
    }
};

TEST_F(LabelsCli, LabelsOnAnotherGridAreBadInputNamingTheFile) {
    writeScan();
    const fs::path labels =
        writeLabels(labelVolume(glm::ivec3(kScanSide, kScanSide, 20), VoxelType::I16,
                                glm::dvec3(1.0), [](int, int, int) { return 1000.0; }));
    const fs::path scene = writeScene();
    const CommandResult r = render(scene);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(labels.string()), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("grid"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("24 x 24 x 20"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames")) << "nothing may be written";
    // validate reads the files too, and refuses them the same way.
    const CommandResult v = runCutaway("validate " + scene.string());
    EXPECT_EQ(v.code, 2) << v.output;
    EXPECT_NE(v.output.find(labels.string() + ": the label volume's grid is 24 x 24 x 20"),
              std::string::npos)
        << v.output;
}

// validate reads what a render reads: a label file on the scan's grid passes,
// negative ids do not, and a volume file that cannot be read is named.
TEST_F(LabelsCli, ValidateReadsTheVolumeAndLabelFiles) {
    const fs::path scan = writeScan();
    writeLabels(labelVolume(glm::ivec3(kScanSide), VoxelType::I16, glm::dvec3(1.0),
                            [](int x, int y, int z) { return shellAndCore(x, y, z); }));
    const fs::path scene = writeScene();
    const CommandResult good = runCutaway("validate " + scene.string());
    EXPECT_EQ(good.code, 0) << good.output;
    const fs::path labels =
        writeLabels(labelVolume(glm::ivec3(kScanSide), VoxelType::I16, glm::dvec3(1.0),
                                [](int x, int, int) { return x == 3 ? -1.0 : 1000.0; }));
    const CommandResult negative = runCutaway("validate " + scene.string());
    EXPECT_EQ(negative.code, 2) << negative.output;
    EXPECT_NE(negative.output.find(labels.string() + ": label ids must not be negative"),
              std::string::npos)
        << negative.output;
    // A scan cut short: its header promises more voxels than the file holds.
    const auto size = fs::file_size(scan);
    fs::resize_file(scan, size - 1000);
    const CommandResult cut = runCutaway("validate " + scene.string());
    EXPECT_EQ(cut.code, 2) << cut.output;
    EXPECT_NE(cut.output.find(scan.string()), std::string::npos) << cut.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames")) << "validate writes nothing";
}

TEST_F(LabelsCli, LabelsWithAnotherSpacingAreBadInputNamingTheFile) {
    writeScan();
    const fs::path labels =
        writeLabels(labelVolume(glm::ivec3(kScanSide), VoxelType::I16, glm::dvec3(1.0, 1.0, 2.0),
                                [](int, int, int) { return 1000.0; }));
    const CommandResult r = render(writeScene());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(labels.string()), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("spacing"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("grid"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames")) << "nothing may be written";
}

TEST_F(LabelsCli, FloatLabelsAreBadInput) {
    writeScan();
    const fs::path labels =
        writeLabels(labelVolume(glm::ivec3(kScanSide), VoxelType::F32, glm::dvec3(1.0),
                                [](int x, int y, int z) { return shellAndCore(x, y, z); }));
    const CommandResult r = render(writeScene());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(labels.string()), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("integers"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("float32"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames")) << "nothing may be written";
}

TEST_F(LabelsCli, NegativeLabelIdsAreBadInput) {
    writeScan();
    const fs::path labels =
        writeLabels(labelVolume(glm::ivec3(kScanSide), VoxelType::I16, glm::dvec3(1.0),
                                [](int x, int, int) { return x == 3 ? -1.0 : 1000.0; }));
    const CommandResult r = render(writeScene());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(labels.string()), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("negative"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames")) << "nothing may be written";
}

TEST_F(LabelsCli, IdsBeyond255ClassifyByLabelAndAlignASegment) {
    writeScan();
    writeLabels(labelVolume(glm::ivec3(kScanSide), VoxelType::I16, glm::dvec3(1.0),
                            [](int x, int y, int z) { return shellAndCore(x, y, z); }));
    const fs::path scene = writeScene(R"("transfer": {
        "points": [ { "value": 0, "color": [0.9, 0.6, 0.5], "alpha": 0 },
                    { "value": 255, "color": [0.9, 0.6, 0.5], "alpha": 0.4 } ],
        "labels": [ { "labels": ["core"],
                      "points": [ { "value": 0, "color": [1, 1, 0.8], "alpha": 0.2 },
                                  { "value": 255, "color": [1, 1, 0.8], "alpha": 0.9 } ] } ] },)");
    const CommandResult r = render(scene);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(r.output.empty()) << "not a terminal: nothing but errors: " << r.output;
    const fs::path exr = m_dir / "frames" / "labels_0000.exr";
    ASSERT_TRUE(fs::exists(exr));
    const Image image = readExr(exr);
    EXPECT_EQ(image.width, 48);
    EXPECT_EQ(image.height, 48);
    // The segment mask the frame read is recorded in the header, with the id.
    EXPECT_EQ(readExrStringAttribute(exr, "cutaway/note0"),
              "operator 0 (peeler): segment mask of labels 2000");

    // Control: the table listed for 208 (2000 mod 256), which no voxel carries,
    // so every sample takes /transfer/points. Were ids cut to 8 bits, the core
    // would match 208 and the two images would be the same.
    const fs::path other = m_dir / "frames" / "other_####.exr";
    const CommandResult control =
        runCutaway("render " + scene.string() + " --size 48x48 -o " + other.string() +
                   " --set /transfer/labels/0/labels/0=208");
    ASSERT_EQ(control.code, 0) << control.output;
    const Image plain = readExr(m_dir / "frames" / "other_0000.exr");
    ASSERT_EQ(plain.rgba.size(), image.rgba.size());
    double difference = 0.0;
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
        difference = std::max(difference, double(std::abs(image.rgba[i] - plain.rgba[i])));
    EXPECT_GT(difference, 0.05) << "the core's own transfer function must show";
}

TEST_F(LabelsCli, SurfaceAlignmentRecordsOtsusThresholdInTheHeader) {
    const fs::path scene = write("scene.json", R"({
      "version": 1,
      "volume": { "phantom": "head", "size": [24, 24, 24] },
      "operators": [ { "type": "peeler",
        "placement": { "translate": [0, 0, 6], "scale": [20, 20, 12] },
        "resolution": 16,
        "alignment": { "mode": "surface", "depth": 2 } } ],
      "output": { "pattern": "frames/surface_####.exr" }
    })");
    const CommandResult r = runCutaway("render " + scene.string() + " --size 48x48");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(r.output.empty()) << "not a terminal: nothing but errors: " << r.output;
    const fs::path exr = m_dir / "frames" / "surface_0000.exr";
    ASSERT_TRUE(fs::exists(exr));
    const std::string note = readExrStringAttribute(exr, "cutaway/note0");
    EXPECT_NE(note.find("operator 0 (peeler): distance field of the object above "),
              std::string::npos)
        << note;
    EXPECT_TRUE(note.ends_with(" (Otsu's threshold)")) << note; // no time: files stay the same
}

TEST_F(LabelsCli, AnEmptySegmentIsBadInputNamingTheOperator) {
    writeScan();
    writeLabels(labelVolume(glm::ivec3(kScanSide), VoxelType::I16, glm::dvec3(1.0),
                            [](int, int, int) { return 1000.0; })); // shell only, no core
    const CommandResult r = render(writeScene());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("operator 0 (peeler)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("empty"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames" / "labels_0000.exr")) << "no frame may be written";
}

// A label volume rendered as itself (/volume and /labels name one file) is
// read and held once: the scan is its own label volume, checked as labels
// are. It renders as with a copy of the file for labels.
TEST_F(LabelsCli, ALabelVolumeRenderedAsItselfIsReadOnce) {
    writeLabels(labelVolume(glm::ivec3(kScanSide), VoxelType::I16, glm::dvec3(1.0),
                            [](int x, int y, int z) { return shellAndCore(x, y, z); }));
    fs::copy_file(m_dir / "labels.nrrd", m_dir / "copy.nrrd");
    // The scan is labels.nrrd, its label volume `file`.
    const auto sceneWith = [&](const std::string& file) {
        return write("scene.json", R"({
          "version": 1,
          "volume": { "file": "labels.nrrd" },
          "labels": { "file": ")" + file +
                                       R"(", "names": { "shell": 1000, "core": 2000 } },
          "transfer": {
            "points": [ { "value": 0, "color": [0.9, 0.6, 0.5], "alpha": 0 },
                        { "value": 2000, "color": [0.9, 0.6, 0.5], "alpha": 0.4 } ],
            "labels": [ { "labels": ["core"],
                          "points": [ { "value": 0, "color": [1, 1, 0.8], "alpha": 0.2 },
                                      { "value": 2000, "color": [1, 1, 0.8], "alpha": 0.9 } ] } ] },
          "operators": [ { "type": "peeler",
            "placement": { "translate": [0, 0, 6], "scale": [20, 20, 12] },
            "resolution": 16,
            "alignment": { "mode": "segment", "labels": ["core"], "band": 2 } } ],
          "output": { "pattern": "frames/labels_####.exr" }
        })");
    };
    std::vector<Image> images;
    for (const std::string labels : {"labels.nrrd", "copy.nrrd"}) {
        SCOPED_TRACE(labels);
        const fs::path scene = sceneWith(labels);
        const Scene parsed = loadScene(scene);
        const auto scan = std::make_shared<const Volume>(job::loadSceneVolume(parsed));
        const auto read = job::loadSceneLabels(parsed, scan);
        ASSERT_TRUE(read);
        if (labels == "labels.nrrd") {
            EXPECT_EQ(read.get(), scan.get()) << "the scan is its own label volume";
        } else {
            EXPECT_NE(read.get(), scan.get());
            EXPECT_EQ(read->data, scan->data);
        }
        const CommandResult r = render(scene);
        ASSERT_EQ(r.code, 0) << r.output;
        images.push_back(readExr(m_dir / "frames" / "labels_0000.exr"));
    }
    ASSERT_EQ(images[0].rgba.size(), images[1].rgba.size());
    EXPECT_EQ(images[0].rgba, images[1].rgba);
    double alpha = 0.0;
    for (std::size_t i = 3; i < images[0].rgba.size(); i += 4)
        alpha += images[0].rgba[i];
    EXPECT_GT(alpha, 50.0) << "the volume must show for the comparison to mean much";

    // The checks of a label volume still apply to a scan used as its labels.
    writeLabels(labelVolume(glm::ivec3(kScanSide), VoxelType::F32, glm::dvec3(1.0),
                            [](int x, int y, int z) { return shellAndCore(x, y, z); }));
    const CommandResult bad = render(sceneWith("labels.nrrd"));
    EXPECT_EQ(bad.code, 2) << bad.output;
    EXPECT_NE(bad.output.find("integers"), std::string::npos) << bad.output;
}

} // namespace
} // namespace cutaway::test
