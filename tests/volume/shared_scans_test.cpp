// The real scans in ../shared/data load with the dims, voxel type and spacing
// their README states. Skipped, with a message, when that folder is absent.
#include "volume_test_util.hpp"

namespace cutaway::test {
namespace {

struct Scan {
    const char* file;
    glm::ivec3 dims;
    VoxelType type;
    glm::dvec3 spacing;
};

const Scan kScans[] = {
    {"headsq.nrrd", {64, 64, 93}, VoxelType::U16, {3.2, 3.2, 1.5}},
    {"chest_ct.nrrd", {256, 256, 133}, VoxelType::U8, {1.40625, 1.40625, 2.5}},
    {"ct_head.nii.gz", {208, 256, 225}, VoxelType::U8, {1, 1, 1}},
    {"carp.nii.gz", {256, 512, 256}, VoxelType::U8, {1, 1, 1}},
    {"brain_t1.nii.gz", {256, 256, 256}, VoxelType::U8, {1, 1, 1}},
    {"brain_labels.nii.gz", {256, 256, 256}, VoxelType::I16, {1, 1, 1}},
    {"frog_labels.nii.gz", {500, 470, 136}, VoxelType::U8, {1, 1, 1.5}},
};

// Names the scan in test output instead of dumping its bytes.
void PrintTo(const Scan& scan, std::ostream* os) {
    *os << scan.file;
}

class SharedScans : public ::testing::TestWithParam<Scan> {};

TEST_P(SharedScans, LoadWithTheirStatedShape) {
    const std::filesystem::path folder(CUTAWAY_SHARED_DATA);
    const Scan& scan = GetParam();
    if (!std::filesystem::exists(folder))
        GTEST_SKIP() << "shared data folder not found at " << folder << ": real-scan tests skipped";
    const Volume v = readVolume(folder / scan.file);
    EXPECT_EQ(v.dims, scan.dims);
    EXPECT_EQ(v.type, scan.type) << voxelTypeName(v.type);
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(v.spacing[a], scan.spacing[a], 1e-4) << a;
    const ValueRange r = valueRange(v);
    EXPECT_LT(r.min, r.max) << "a constant volume";
    if (std::string(scan.file) == "brain_labels.nii.gz") {
        EXPECT_EQ(r.max, 12175.0) << "FreeSurfer label ids above 255 must survive";
    }
}

// Where the scans lie in LPS, from their headers: brain_t1's sform (code 2)
// flips x and maps j to inferior and k to posterior (FreeSurfer's conformed
// LIA orientation); ct_head's sform (code 1) is diagonal in RAS; chest_ct is
// an LPS NRRD with diagonal space directions at the origin.
TEST(SharedScanGeometry, OrientationsInLps) {
    const std::filesystem::path folder(CUTAWAY_SHARED_DATA);
    if (!std::filesystem::exists(folder))
        GTEST_SKIP() << "shared data folder not found at " << folder << ": real-scan tests skipped";
    const auto expectNear = [](glm::dvec3 got, glm::dvec3 want, const char* what) {
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(got[a], want[a], 1e-4) << what << " [" << a << "]";
    };
    const Volume brain = readVolume(folder / "brain_t1.nii.gz");
    EXPECT_EQ(brain.space, Space::LPS);
    expectNear(brain.direction[0], {1, 0, 0}, "brain i");
    expectNear(brain.direction[1], {0, 0, -1}, "brain j");
    expectNear(brain.direction[2], {0, -1, 0}, "brain k");
    expectNear(brain.origin, {-121.76697, 118.48401, 127.56124}, "brain origin");
    // The last voxel, from the sform rows: RAS (121.76697 - 255, -118.48401 + 255,
    // 127.56124 - 255) (pixdim and the sform's columns are 1 within 1.2e-7).
    expectNear(brain.physicalPosition({255, 255, 255}), {133.23302, -136.51596, -127.43873},
               "brain corner");

    const Volume ct = readVolume(folder / "ct_head.nii.gz");
    EXPECT_EQ(ct.space, Space::LPS);
    expectNear(ct.direction[0], {-1, 0, 0}, "ct i");
    expectNear(ct.direction[1], {0, -1, 0}, "ct j");
    expectNear(ct.direction[2], {0, 0, 1}, "ct k");
    expectNear(ct.origin, {104, 128, -112}, "ct origin");

    const Volume chest = readVolume(folder / "chest_ct.nrrd");
    EXPECT_EQ(chest.space, Space::LPS);
    EXPECT_EQ(chest.direction, glm::dmat3(1.0));
    EXPECT_EQ(chest.origin, glm::dvec3(0.0));
}

INSTANTIATE_TEST_SUITE_P(Data, SharedScans, ::testing::ValuesIn(kScans), [](const auto& param) {
    std::string name = param.param.file;
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
});

} // namespace
} // namespace cutaway::test
