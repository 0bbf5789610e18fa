#pragma once
// Running the cutaway binary from tests, with the validation layer on.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace cutaway::test {

struct CommandResult {
    int code = -1;      ///< exit code; 128 + signal if the process was killed
    std::string output; ///< stdout and stderr together
};

/// Runs `PROGRAM ARGS` (or `PREFIX PROGRAM ARGS`) through the shell.
inline CommandResult runProgram(const std::string& program, const std::string& args,
                                const std::string& prefix = "") {
    const std::string cmd = "CUTAWAY_VALIDATION=1 " + prefix + " " + program + " " + args + " 2>&1";
    CommandResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe))
        r.output.append(buf, n);
    const int status = pclose(pipe);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return r;
}

/// Runs `cutaway ARGS` (or `PREFIX cutaway ARGS`) through the shell.
inline CommandResult runCutaway(const std::string& args, const std::string& prefix = "") {
    return runProgram(CUTAWAY_BINARY, args, prefix);
}

/// A fresh folder per test, removed afterwards.
class CliTest : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = std::filesystem::temp_directory_path() /
                ("cutaway_cli_" +
                 std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        std::filesystem::remove_all(m_dir);
        std::filesystem::create_directories(m_dir);
    }
    void TearDown() override { std::filesystem::remove_all(m_dir); }

    std::filesystem::path write(const std::string& name, const std::string& text) {
        std::ofstream(m_dir / name) << text;
        return m_dir / name;
    }
    static std::vector<std::string> files(const std::filesystem::path& dir) {
        std::vector<std::string> names;
        if (!std::filesystem::exists(dir)) return names;
        for (const auto& e : std::filesystem::directory_iterator(dir))
            names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }
    std::filesystem::path m_dir;
};

} // namespace cutaway::test
