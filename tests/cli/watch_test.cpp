// `cutaway watch` end to end, with the validation layer on: the binary runs
// in the background; the test edits the scene on disk and waits (up to a
// minute each) for what the watch must do: a first preview; a new preview
// after an edit; an invalid edit printed as an error, the watch going on; a
// new preview after the next valid edit; and an end at SIGTERM (a background job ignores SIGINT).
#include "cli_util.hpp"
#include "volume/phantom.hpp"
#include "volume/volume.hpp"

#include <chrono>
#include <csignal>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <thread>

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string contentOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

class Watch : public CliTest {
protected:
    void TearDown() override {
        if (m_pid > 0) ::kill(m_pid, SIGKILL);
        CliTest::TearDown();
    }

    std::string scene(const std::string& background) {
        return R"({"version": 1, "volume": {"phantom": "head", "size": [24, 24, 24]},
            "render": {"size": [24, 24], "background": )" +
               background + "}}";
    }

    // Writes the scene whole under another name and renames it, as editors do.
    void edit(const std::string& text) {
        write("scene.tmp", text);
        fs::rename(m_dir / "scene.tmp", m_dir / "scene.json");
    }

    void start() {
        // exec: the background job's pid is the watch's own.
        const std::string command = "(cd " + m_dir.string() + " && exec env CUTAWAY_VALIDATION=1 " +
                                    CUTAWAY_BINARY + " watch scene.json -o p.png --poll 0.05) > " +
                                    (m_dir / "log.txt").string() + " 2>&1 & echo $! > " +
                                    (m_dir / "pid.txt").string();
        ASSERT_EQ(std::system(command.c_str()), 0);
        m_pid = std::stoi(contentOf(m_dir / "pid.txt"));
    }

    // Waits until `done` holds, for a minute at most.
    bool waitFor(const std::function<bool()>& done) {
        for (auto end = std::chrono::steady_clock::now() + 60s;
             std::chrono::steady_clock::now() < end; std::this_thread::sleep_for(50ms))
            if (done()) return true;
        return false;
    }

    std::size_t count(const std::string& text) {
        const std::string log = contentOf(m_dir / "log.txt");
        std::size_t n = 0;
        for (std::size_t at = log.find(text); at != std::string::npos; at = log.find(text, at + 1))
            ++n;
        return n;
    }

    pid_t m_pid = -1;
};

TEST_F(Watch, EditsGiveNewPreviewsAndAnInvalidOneAnErrorUntilSigterm) {
    edit(scene("[0.1, 0.1, 0.1]"));
    start();
    const fs::path preview = m_dir / "p.png";
    ASSERT_TRUE(waitFor([&] { return count("updated in") == 1; })) << contentOf(m_dir / "log.txt");
    const std::string first = contentOf(preview);
    EXPECT_FALSE(first.empty());

    edit(scene("[0.8, 0.2, 0.2]"));
    ASSERT_TRUE(waitFor([&] { return count("updated in") == 2; })) << contentOf(m_dir / "log.txt");
    const std::string second = contentOf(preview);
    EXPECT_NE(second, first) << "the edit shows";

    edit(R"({"version": 1, "volume": {"phantom": "head"}, "camrea": {}})");
    ASSERT_TRUE(waitFor([&] { return count("did you mean \"camera\"") == 1; }))
        << contentOf(m_dir / "log.txt");
    EXPECT_EQ(contentOf(preview), second) << "an invalid scene leaves the preview";

    edit(scene("[0.2, 0.8, 0.2]"));
    ASSERT_TRUE(waitFor([&] { return count("updated in") == 3; })) << contentOf(m_dir / "log.txt");
    EXPECT_NE(contentOf(preview), second);

    ::kill(m_pid, SIGTERM);
    EXPECT_TRUE(waitFor([&] { return ::kill(m_pid, 0) != 0 && count("stopped watching") == 1; }))
        << contentOf(m_dir / "log.txt");
    m_pid = -1;
    EXPECT_EQ(count("validation"), 0u) << contentOf(m_dir / "log.txt");
}

// A file the scene reads, rewritten under the same name: the renderer's
// caches know the volume by its name, so the watch starts them anew.
TEST_F(Watch, ARewrittenVolumeFileGivesANewPreview) {
    writeNrrd(m_dir / "v.nrrd", makePhantom("head", {20, 20, 20}).values);
    edit(R"({"version": 1, "volume": {"file": "v.nrrd"}, "render": {"size": [24, 24]}})");
    start();
    ASSERT_TRUE(waitFor([&] { return count("updated in") == 1; })) << contentOf(m_dir / "log.txt");
    const std::string first = contentOf(m_dir / "p.png");
    writeNrrd(m_dir / "v.nrrd", makePhantom("orange", {20, 20, 20}).values);
    ASSERT_TRUE(waitFor([&] { return count("updated in") == 2; })) << contentOf(m_dir / "log.txt");
    EXPECT_NE(contentOf(m_dir / "p.png"), first) << "the new volume shows";
}

// The volume deleted, then written again: the watch reports the missing
// file, and renders once it is back (it watched the scene alone before).
TEST_F(Watch, ADeletedVolumeThatComesBackGivesANewPreview) {
    writeNrrd(m_dir / "v.nrrd", makePhantom("head", {20, 20, 20}).values);
    edit(R"({"version": 1, "volume": {"file": "v.nrrd"}, "render": {"size": [24, 24]}})");
    start();
    ASSERT_TRUE(waitFor([&] { return count("updated in") == 1; })) << contentOf(m_dir / "log.txt");
    const std::string first = contentOf(m_dir / "p.png");
    fs::remove(m_dir / "v.nrrd");
    ASSERT_TRUE(waitFor([&] { return count("waiting for the next change") == 1; }))
        << contentOf(m_dir / "log.txt");
    writeNrrd(m_dir / "v.nrrd", makePhantom("orange", {20, 20, 20}).values);
    ASSERT_TRUE(waitFor([&] { return count("updated in") == 2; })) << contentOf(m_dir / "log.txt");
    EXPECT_NE(contentOf(m_dir / "p.png"), first) << "the volume that came back shows";
}

TEST_F(CliTest, WatchRefusesAPreviewThatIsNotAPng) {
    const fs::path s = write("scene.json", R"({"version": 1, "volume": {"phantom": "head"}})");
    CommandResult r = runCutaway("watch " + s.string() + " -o " + (m_dir / "p.exr").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("expected a .png file name"), std::string::npos) << r.output;
}

} // namespace
} // namespace cutaway::test
