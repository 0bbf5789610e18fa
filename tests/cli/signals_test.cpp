// Signals through the binary: the temporaries a SIGKILL leaves carry their
// host and process, so that --skip-existing removes them and only them.
#include "cli_util.hpp"
#include "io/exr.hpp"
#include "job/render_job.hpp"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <regex>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace cutaway::test {
namespace {

// A turntable of `frames` frames of a small phantom at `pixels`^2.
std::string spinningHead(int frames, int pixels, const std::string& extra = "") {
    return R"({ "version": 1, "volume": { "phantom": "head", "size": [16, 16, 16] },
      "render": { "size": [)" +
           std::to_string(pixels) + "," + std::to_string(pixels) + R"(] },
      "animation": { "frames": [0, )" +
           std::to_string(frames - 1) + R"(], "tracks": [ { "target": "/camera/orbit/azimuth",
        "keys": [ { "frame": 0, "value": 0 }, { "frame": 100, "value": 360 } ] } ] },
      "output": { "pattern": "frames/t_####.exr" })" +
           extra + "}";
}

std::string thisHost() {
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    return name;
}

} // namespace

TEST_F(CliTest, SkipExistingRemovesOnlyTheTemporariesAKilledRunLeft) {
    // Big frames of a tiny volume take long to write: the run is killed
    // (SIGKILL, no handler runs) once a frame's temporary appears.
    const fs::path scene = write("long.json", spinningHead(2000, 2048));
    const std::string frames = (m_dir / "frames").string();
    const fs::path killer =
        write("killer.sh", "\"$@\" & pid=$!\necho $pid > " + (m_dir / "pid").string() +
                               "\nwhile kill -0 $pid && ! ls -a " + frames +
                               " 2>/dev/null | grep -q '[.]tmp-'; do sleep 0.01; done\n"
                               "kill -KILL $pid; wait $pid\n");
    CommandResult killed = runCutaway("render " + scene.string(), "sh " + killer.string());
    EXPECT_EQ(killed.code, 128 + 9) << killed.output;
    std::string pid;
    std::ifstream(m_dir / "pid") >> pid;
    // The temporary names its frame, this host and the killed process.
    const std::regex named("[.](t_[0-9]{4}[.]exr)[.]tmp-" + thisHost() + "-" + pid + "-[0-9]+");
    std::vector<std::string> temporaries, owned;
    int last = 0;
    for (const std::string& name : files(m_dir / "frames")) {
        std::smatch m;
        if (name[0] != '.') continue;
        temporaries.push_back(name);
        EXPECT_TRUE(std::regex_match(name, m, named)) << name;
        if (m.size() > 1) last = std::max(last, std::stoi(m[1].str().substr(2, 4)));
    }
    ASSERT_FALSE(temporaries.empty()) << killed.output;
    // Temporaries that are not this host's stale ones stay: another host's
    // (a shared file system), a live process's (this test), another frame's.
    const std::vector<std::string> others = {".t_0000.exr.tmp-another.host-" + pid + "-0",
                                             ".t_0000.exr.tmp-" + thisHost() + "-" +
                                                 std::to_string(::getpid()) + "-0",
                                             ".t_0399.exr.tmp-" + thisHost() + "-" + pid + "-0"};
    for (const std::string& name : others)
        std::ofstream(m_dir / "frames" / name) << "partial";

    CommandResult resumed = runCutaway("render " + scene.string() +
                                       " --skip-existing --frames 0.." + std::to_string(last));
    EXPECT_EQ(resumed.code, 0) << resumed.output;
    for (const std::string& name : temporaries)
        EXPECT_FALSE(fs::exists(m_dir / "frames" / name)) << name << " was left";
    for (const std::string& name : others)
        EXPECT_TRUE(fs::exists(m_dir / "frames" / name)) << name << " was removed";
    for (int f = 0; f <= last; ++f)
        EXPECT_EQ(readExr(m_dir / "frames" / job::expandPattern("t_####.exr", f)).width, 2048);
}

} // namespace cutaway::test
