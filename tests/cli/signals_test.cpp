// Signals through the binary: SIGHUP and SIGQUIT stop a run as SIGTERM does,
// a closed pipe on stdout and stderr neither kills a run nor hides its
// failures, and the temporaries a SIGKILL leaves carry their host and
// process, so that --skip-existing removes them and only them.
#include "cli_util.hpp"
#include "io/exr.hpp"
#include "job/render_job.hpp"

#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <regex>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace fs = std::filesystem;

namespace cutaway::test {
namespace {

// A turntable of `frames` frames of a small phantom at `pixels`^2.
// `animation`: the animation section in place of the spin (a key is
// written once in a scene).
std::string spinningHead(int frames, int pixels, const std::string& extra = "",
                         const std::string& animation = "") {
    const std::string spin = R"({ "frames": [0, )" + std::to_string(frames - 1) +
                             R"(], "tracks": [ { "target": "/camera/orbit/azimuth",
        "keys": [ { "frame": 0, "value": 0 }, { "frame": 100, "value": 360 } ] } ] })";
    return R"({ "version": 1, "volume": { "phantom": "head", "size": [16, 16, 16] },
      "render": { "size": [)" +
           std::to_string(pixels) + "," + std::to_string(pixels) + R"(] },
      "animation": )" +
           (animation.empty() ? spin : animation) + R"(,
      "output": { "pattern": "frames/t_####.exr" })" +
           extra + "}";
}

std::string thisHost() {
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    return name;
}

// Runs cutaway with `args`, its stdout and stderr a pipe nobody reads, and
// SIGPIPE at its default action (whatever this process does with it).
int runWithClosedOutput(const std::vector<std::string>& args) {
    int fds[2];
    if (::pipe(fds) != 0) return -1;
    ::close(fds[0]); // no reader: every write fails (EPIPE) or raises SIGPIPE
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGPIPE);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
    std::vector<std::string> all{CUTAWAY_BINARY};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& arg : all)
        argv.push_back(arg.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int spawned =
        posix_spawn(&pid, CUTAWAY_BINARY, &actions, &attributes, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    ::close(fds[1]);
    if (spawned != 0) return -1;
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

} // namespace

TEST_F(CliTest, HangupAndQuitStopTheRunAsTermDoes) {
    const fs::path scene = write("long.json", spinningHead(2000, 96));
    for (const auto& [signal, number] : {std::pair{"HUP", 1}, std::pair{"QUIT", 3}}) {
        SCOPED_TRACE(signal);
        fs::remove_all(m_dir / "frames");
        CommandResult r = runCutaway("render " + scene.string() + " --png",
                                     std::string("timeout --preserve-status -s ") + signal + " 2");
        EXPECT_EQ(r.code, 128 + number) << r.output;
        EXPECT_NE(r.output.find("interrupted by signal " + std::to_string(number)),
                  std::string::npos)
            << r.output;
        // Only whole frames, each with its preview; no temporaries.
        const std::vector<std::string> names = files(m_dir / "frames");
        ASSERT_LT(names.size(), 4000u) << "the run was not interrupted";
        std::vector<std::string> expected;
        for (std::size_t f = 0; f < names.size() / 2; ++f) {
            expected.push_back(job::expandPattern("t_####.exr", static_cast<int>(f)));
            expected.push_back(job::expandPattern("t_####.png", static_cast<int>(f)));
        }
        std::sort(expected.begin(), expected.end());
        EXPECT_EQ(names, expected) << "a temporary, a gap or an EXR without its preview";
        for (const std::string& name : names) {
            if (name.ends_with(".exr")) {
                EXPECT_EQ(readExr(m_dir / "frames" / name).width, 96);
            }
        }
    }
}

TEST_F(CliTest, AClosedPipeNeitherEndsTheRunNorHidesItsFailures) {
    // Every frame warns of the operator outside the volume (on stderr).
    const fs::path warned = write(
        "warned.json", spinningHead(4, 16, R"(, "operators": [{ "type": "peeler", "placement": {
            "translate": [500, 0, 0], "scale": [8, 8, 8] } }])"));
    EXPECT_EQ(runWithClosedOutput({"render", warned.string()}), 0);
    EXPECT_EQ(files(m_dir / "frames"),
              (std::vector<std::string>{"t_0000.exr", "t_0001.exr", "t_0002.exr", "t_0003.exr"}));
    EXPECT_EQ(runWithClosedOutput({"validate", warned.string()}), 0);

    // Frames 2 and 3 fail (the field of view leaves its range): exit 2 still.
    fs::remove_all(m_dir / "frames");
    const fs::path failing =
        write("fov.json", spinningHead(4, 16, R"(, "camera": { "fov": 100 })", R"({
            "frames": [0, 3], "tracks": [ { "target": "/camera/fov", "keys": [
            { "frame": 0, "value": 100 }, { "frame": 3, "value": 220 } ] } ] })"));
    EXPECT_EQ(runWithClosedOutput({"render", failing.string()}), 2);
    EXPECT_EQ(files(m_dir / "frames"), (std::vector<std::string>{"t_0000.exr", "t_0001.exr"}));
    // The control: with a reader, the same runs end the same way.
    EXPECT_EQ(runCutaway("render " + failing.string()).code, 2);
}

TEST_F(CliTest, ASignalWhileExportWritesLeavesNoTemporary) {
    // A 256^3 float volume takes a while to compress: the signal comes once
    // its temporary appears.
    const fs::path scene = write("big.json", R"({ "version": 1,
        "volume": { "phantom": "head", "size": [256, 256, 256] } })");
    const fs::path killer =
        write("killer.sh", "\"$@\" & pid=$!\nwhile kill -0 $pid && ! ls -a " + m_dir.string() +
                               " | grep -q '[.]tmp-'; do sleep 0.01; done\n"
                               "kill -HUP $pid; wait $pid\n");
    CommandResult r = runCutaway("export " + scene.string() + " -o " + (m_dir / "x.nrrd").string(),
                                 "sh " + killer.string());
    EXPECT_EQ(r.code, 128 + SIGHUP) << r.output;
    EXPECT_EQ(files(m_dir), (std::vector<std::string>{"big.json", "killer.sh"}));
}

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
    EXPECT_EQ(killed.code, 128 + SIGKILL) << killed.output;
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
