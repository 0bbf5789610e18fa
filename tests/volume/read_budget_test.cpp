// The read budget (volume/read_budget.hpp): a volume whose header declares
// more than reading may take is refused before anything is allocated or
// decompressed, naming the file and the budget, in every reader; the same
// file under the default budget gets as far as its (truncated) data.
#include "core/error.hpp"
#include "volume/read_budget.hpp"
#include "volume_test_util.hpp"

namespace cutaway::test {
namespace {

// A budget for one test, the default restored after it.
class ReadBudget : public VolumeFiles {
protected:
    void TearDown() override {
        setReadBudget(std::nullopt);
        VolumeFiles::TearDown();
    }
};

// 512^3 float32 (512 MiB) declared by a gzip'd NIfTI and by a MetaImage
// whose data holds a few bytes.
TEST_F(ReadBudget, ADeclaredSizeOverTheBudgetIsRefusedBeforeReading) {
    NiftiHeader h;
    h.dims[1] = h.dims[2] = h.dims[3] = 512;
    h.datatype = 16;
    h.bitpix = 32;
    const auto nifti = writeFile("big.nii.gz", gzip(h.bytes() + "abcd"));
    const auto mha = writeFile("big.mha", "NDims = 3\nDimSize = 512 512 512\nElementType = "
                                          "MET_FLOAT\nElementDataFile = LOCAL\nabcd");
    for (const auto& file : {nifti, mha}) {
        SCOPED_TRACE(file.string());
        setReadBudget(std::uint64_t{64} << 20);
        const std::string refused = inputError([&] { readVolume(file); });
        EXPECT_NE(refused.find(file.string() + ": its 512x512x512 float32 voxels need 512 MiB, "
                                               "more than the 64 MiB reading may take"),
                  std::string::npos)
            << refused;
        setReadBudget(std::nullopt);
        const std::string truncated = inputError([&] { readVolume(file); });
        EXPECT_NE(truncated.find("truncated"), std::string::npos)
            << "control: the default budget reads on to the data: " << truncated;
    }
    EXPECT_GE(defaultReadBudget(), std::uint64_t{256} << 20);
}

} // namespace
} // namespace cutaway::test
