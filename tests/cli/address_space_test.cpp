// Rendering under an address-space limit (RLIMIT_AS, set here with
// prlimit(1) as an HPC scheduler's `ulimit -v` would): a frame that needs
// more ends in exit code 1 naming the limit, before the device is made
// (driver and image) or once the volume is known; one within it renders.
// Skipped under the sanitizers, which reserve terabytes of address space of
// their own.
#include "cli_util.hpp"
#include "job/address_space.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define CUTAWAY_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) ||                         \
    __has_feature(memory_sanitizer)
#define CUTAWAY_SANITIZED 1
#endif
#endif

namespace fs = std::filesystem;

namespace cutaway::test {
namespace {

constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;

std::string phantomScene(int side) {
    const std::string s = std::to_string(side);
    return R"({ "version": 1, "volume": { "phantom": "head", "size": [)" + s + "," + s + "," + s +
           R"(] }, "render": { "size": [64, 64] }, "output": { "pattern": "frames/f_####.exr" } })";
}

CommandResult renderUnder(std::uint64_t limit, const fs::path& scene) {
    return runCutaway("render " + scene.string(), "prlimit --as=" + std::to_string(limit));
}

} // namespace

TEST_F(CliTest, AFrameNeedingMoreAddressSpaceThanTheLimitEndsInExitOneNamingIt) {
#ifdef CUTAWAY_SANITIZED
    GTEST_SKIP() << "the sanitizers reserve address space of their own";
#endif
    if (runProgram("prlimit", "--version").code != 0) GTEST_SKIP() << "no prlimit(1)";
    // What the frames need, as the renderer estimates it (this environment's
    // threads, and the validation layer runCutaway turns on).
    ::setenv("CUTAWAY_VALIDATION", "1", 1);
    const fs::path scene = write("big.json", phantomScene(256));
    Scene parsed = loadScene(scene);
    const Volume volume = Volume::allocate({256, 256, 256}, VoxelType::U8);
    const std::uint64_t device = job::addressSpaceNeed(parsed).total();
    const std::uint64_t frame = job::addressSpaceNeed(parsed, &volume).total();
    ASSERT_GT(frame - device, 100 * kMiB) << "the volume's share must tell the two checks apart";

    // Below what the driver needs: refused before the device is made.
    const std::uint64_t small = 300 * kMiB;
    CommandResult r = renderUnder(small, scene);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(
        r.output.find("address-space limit (ulimit -v) of " + std::to_string(small >> 10) + " KiB"),
        std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames"));

    // Enough for the device, not for the volume: refused before its upload.
    const std::uint64_t between = device + (frame - device) / 2;
    r = renderUnder(between, scene);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("address-space limit (ulimit -v) of " + std::to_string(between >> 10) +
                            " KiB"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("the volume and its textures"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(m_dir / "frames"));

    // The control: within the limit, the frame renders.
    r = renderUnder(frame + 16 * kMiB, scene);
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(m_dir / "frames" / "f_0000.exr"));
}

} // namespace cutaway::test
