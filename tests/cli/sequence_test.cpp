// Sequences through the binary: turntables, shards, resuming, interruption,
// per-frame failures, EXR headers; every example scene and bad scene.
#include "cli_util.hpp"
#include "core/error.hpp"
#include "io/exr.hpp"
#include "io/exr_header.hpp"
#include "job/render_job.hpp"

#include <algorithm>
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sys/stat.h>

namespace fs = std::filesystem;

namespace cutaway::test {
namespace {

// A 6-frame turntable of a small phantom; azimuth = 60 * frame.
std::string turntable(int lastFrame = 5, int size = 24, int pixels = 32) {
    const std::string end = std::to_string(lastFrame + 1);
    return R"({ "version": 1,
      "volume": { "phantom": "head", "size": [)" +
           std::to_string(size) + "," + std::to_string(size) + "," + std::to_string(size) +
           R"(] },
      "camera": { "orbit": { "elevation": 10 } },
      "render": { "size": [)" +
           std::to_string(pixels) + "," + std::to_string(pixels) + R"(] },
      "animation": { "frames": [0, )" +
           std::to_string(lastFrame) + R"(], "tracks": [
        { "target": "/camera/orbit/azimuth",
          "keys": [ { "frame": 0, "value": 0 }, { "frame": )" +
           end + R"(, "value": )" + std::to_string(60 * (lastFrame + 1)) + R"( } ] } ] },
      "output": { "pattern": "frames/t_####.exr" } })";
}

std::vector<std::string> frameNames(int first, int last) {
    std::vector<std::string> names;
    for (int f = first; f <= last; ++f)
        names.push_back(job::expandPattern("t_####.exr", f));
    return names;
}

using Stamps = std::map<std::string, fs::file_time_type>;
Stamps stamps(const fs::path& dir) {
    Stamps s;
    for (const auto& e : fs::directory_iterator(dir))
        s[e.path().filename().string()] = fs::last_write_time(e.path());
    return s;
}

} // namespace

TEST_F(CliTest, TurntableRendersEveryFrameWithItsHeader) {
    const fs::path scene = write("turn.json", turntable());
    CommandResult r = runCutaway("render " + scene.string());
    ASSERT_EQ(r.code, 0) << r.output;
    ASSERT_EQ(files(m_dir / "frames"), frameNames(0, 5));
    const fs::path f3 = m_dir / "frames" / "t_0003.exr";
    EXPECT_EQ(readExrStringAttribute(f3, "cutaway/frame"), "3");
    EXPECT_FALSE(readExrStringAttribute(f3, "cutaway/version").empty());
    const auto evaluated = nlohmann::json::parse(readExrStringAttribute(f3, "cutaway/scene"));
    EXPECT_DOUBLE_EQ(evaluated["camera"]["orbit"]["azimuth"].get<double>(), 180.0);
    // The view turns: frames 0 and 3 (opposite sides) differ.
    Image a = readExr(m_dir / "frames" / "t_0000.exr"), b = readExr(f3);
    double diff = 0.0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
        diff += std::abs(a.rgba[i] - b.rgba[i]);
    EXPECT_GT(diff, 1.0);
}

TEST_F(CliTest, ShardsTogetherWriteEachFrameExactlyOnce) {
    const fs::path scene = write("turn.json", turntable(7));
    std::multiset<std::string> all;
    for (int i = 0; i < 3; ++i) {
        const fs::path out = m_dir / ("shard" + std::to_string(i));
        CommandResult r = runCutaway("render " + scene.string() + " --shard " + std::to_string(i) +
                                     "/3 -o " + (out / "t_####.exr").string());
        ASSERT_EQ(r.code, 0) << r.output;
        for (const std::string& name : files(out)) {
            const int frame = std::stoi(name.substr(2, 4));
            EXPECT_EQ(frame % 3, i) << name << " rendered by shard " << i;
            all.insert(name);
        }
    }
    const auto expected = frameNames(0, 7);
    EXPECT_EQ(all, std::multiset<std::string>(expected.begin(), expected.end()));
}

TEST_F(CliTest, SkipExistingRendersOnlyWhatIsMissing) {
    const fs::path scene = write("turn.json", turntable());
    ASSERT_EQ(runCutaway("render " + scene.string()).code, 0);
    const Stamps before = stamps(m_dir / "frames");
    CommandResult again = runCutaway("render " + scene.string() + " --skip-existing");
    ASSERT_EQ(again.code, 0) << again.output;
    EXPECT_EQ(stamps(m_dir / "frames"), before) << "--skip-existing rewrote a frame";

    fs::remove(m_dir / "frames" / "t_0002.exr");
    ASSERT_EQ(runCutaway("render " + scene.string() + " --skip-existing").code, 0);
    Stamps after = stamps(m_dir / "frames");
    ASSERT_EQ(after.size(), before.size());
    for (const auto& [name, time] : before) {
        if (name != "t_0002.exr") {
            EXPECT_EQ(after[name], time) << name;
        }
    }
}

TEST_F(CliTest, FramesOptionSelectsARange) {
    const fs::path scene = write("turn.json", turntable());
    CommandResult r = runCutaway("render " + scene.string() + " --frames 2..4");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(files(m_dir / "frames"), frameNames(2, 4));
    EXPECT_EQ(runCutaway("render " + scene.string() + " --frames 4..2").code, 2);
    EXPECT_EQ(runCutaway("render " + scene.string() + " --shard 3/3").code, 2);
}

// Output paths that would lose frames or replace something that is not a
// file are refused before the device is opened, naming -o; nothing is
// written, and what was there stays.
TEST_F(CliTest, OutputPathsThatWouldLoseFramesAreRefusedBeforeRendering) {
    const fs::path scene = write("turn.json", turntable());
    const auto refused = [&](const std::string& args, const std::string& why) {
        CommandResult r = runCutaway("render " + scene.string() + " " + args);
        EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("-o "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(why), std::string::npos) << r.output;
    };
    // No frame number: six frames would each replace the one before; also
    // when each shard renders one frame (shards share the folder).
    refused("-o " + (m_dir / "all.exr").string(), "no frame number");
    refused("--frames 0..1 --shard 1/2 -o " + (m_dir / "all.exr").string(), "no frame number");
    // Two frame numbers: the second would stay literal.
    refused("-o " + (m_dir / "take#/t_####.exr").string(), "2 frame numbers");
    refused("-o " + (m_dir / "t_####_%04d.exr").string(), "2 frame numbers");
    // The EXR named .png: its preview would replace it.
    refused("--frames 0 --png -o " + (m_dir / "t_####.png").string(), "PNG preview");
    // A name longer than a folder entry, with its temporary's, can hold; a
    // width past any integer's range is no crash.
    refused("--frames 0 -o " + (m_dir / "t_%0156d.exr").string(), "longer than the 156 bytes");
    refused("--frames 0 -o " + (m_dir / "t_%099999999999999999999d.exr").string(),
            "frame 0: cannot write");
    // A named pipe (as a device such as /dev/null would be) is not replaced.
    const fs::path pipe = m_dir / "p_0001.exr";
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    refused("--frames 0..2 -o " + (m_dir / "p_####.exr").string(),
            "named pipe (FIFO), which cutaway does not replace");
    EXPECT_TRUE(fs::is_fifo(pipe));
    EXPECT_EQ(files(m_dir), (std::vector<std::string>{"p_0001.exr", "turn.json"}));

    // One frame needs no number; a link is written through.
    CommandResult one =
        runCutaway("render " + scene.string() + " --frames 3 -o " + (m_dir / "one.exr").string());
    EXPECT_EQ(one.code, 0) << one.output;
    EXPECT_EQ(readExrStringAttribute(m_dir / "one.exr", "cutaway/frame"), "3");
    fs::create_directories(m_dir / "store");
    fs::create_symlink(m_dir / "store" / "real.exr", m_dir / "link_0000.exr");
    CommandResult link = runCutaway("render " + scene.string() + " --frames 0 -o " +
                                    (m_dir / "link_####.exr").string());
    EXPECT_EQ(link.code, 0) << link.output;
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(m_dir / "link_0000.exr")));
    EXPECT_EQ(readExrStringAttribute(m_dir / "store" / "real.exr", "cutaway/frame"), "0");
}

// Frame numbers are padded to any width; none is cut short.
TEST(Pattern, PadsFrameNumbersToAnyWidth) {
    EXPECT_EQ(job::expandPattern("f_####.exr", 8), "f_0008.exr");
    EXPECT_EQ(job::expandPattern("f_##.exr", 12345), "f_12345.exr");
    EXPECT_EQ(job::expandPattern("f_%d.exr", 8), "f_8.exr");
    EXPECT_EQ(job::expandPattern("f_%4d.exr", 8), "f_   8.exr");
    EXPECT_EQ(job::expandPattern("g_%040d.exr", 9), "g_" + std::string(39, '0') + "9.exr");
    EXPECT_EQ(job::expandPattern(std::string(40, '#'), 10), std::string(38, '0') + "10");
    EXPECT_EQ(job::framePlaceholders("a/b.exr"), 0);
    EXPECT_EQ(job::framePlaceholders("a/b_####.exr"), 1);
    EXPECT_EQ(job::framePlaceholders("a#/b_%03d.exr"), 2);
    // "%%" is a literal '%', as in printf, and no placeholder; a lone '%' stays.
    EXPECT_EQ(job::expandPattern("f_%%d_50%_%02d.exr", 7), "f_%d_50%_07.exr");
    EXPECT_EQ(job::expandPattern("f_%%%d_##.exr", 7), "f_%7_07.exr");
    EXPECT_EQ(job::framePlaceholders("f_%%d.exr"), 0);
    EXPECT_EQ(job::framePlaceholders("f_%%%d.exr"), 1);
    EXPECT_EQ(job::expandPattern("f_%%d.exr", 3), "f_%d.exr");
}

// --set wins over a track of the same value; the header records the frame
// as rendered: tracks applied, no /animation, the size of the image.
TEST_F(CliTest, SetOverridesATrackAndTheHeaderRecordsTheFrameAsRendered) {
    const fs::path scene = write("turn.json", turntable());
    CommandResult r = runCutaway("render " + scene.string() +
                                 " --frames 3 --size 24x20 --set /camera/orbit/azimuth=90");
    ASSERT_EQ(r.code, 0) << r.output;
    const fs::path f3 = m_dir / "frames" / "t_0003.exr";
    const auto recorded = nlohmann::json::parse(readExrStringAttribute(f3, "cutaway/scene"));
    EXPECT_DOUBLE_EQ(recorded["camera"]["orbit"]["azimuth"].get<double>(), 90.0);
    EXPECT_FALSE(recorded.contains("animation")) << recorded.dump();
    EXPECT_EQ(recorded["render"]["size"], nlohmann::json::parse("[24, 20]"));
    // The recorded scene renders the same image on its own.
    const fs::path again = write("again.json", recorded.dump());
    CommandResult a = runCutaway("render " + again.string() + " -o " + (m_dir / "a.exr").string());
    ASSERT_EQ(a.code, 0) << a.output;
    EXPECT_EQ(readExr(m_dir / "a.exr").rgba, readExr(f3).rgba);
}

// Frame numbers on the command line stop where a scene's do.
TEST_F(CliTest, FrameNumbersPastTheLimitAreRefused) {
    const fs::path scene = write("turn.json", turntable());
    for (const char* args : {"render --frames 0..1000001", "render --frames 2147483647",
                             "export --frame 1000001 -o x.nrrd"}) {
        SCOPED_TRACE(args);
        const std::string a(args);
        const std::string command =
            a.substr(0, a.find(' ')) + " " + scene.string() + a.substr(a.find(' '));
        CommandResult r = runCutaway(command);
        EXPECT_EQ(r.code, 2) << r.output;
        EXPECT_NE(r.output.find("[0, 1000000]"), std::string::npos) << r.output;
    }
    EXPECT_FALSE(fs::exists(m_dir / "frames"));
}

TEST_F(CliTest, InterruptedSequenceLeavesOnlyWholeFrames) {
    const fs::path scene = write("long.json", turntable(399, 48, 96));
    // A signal after a second, mid-sequence (frame n may be being written
    // while n + 1 renders); --preserve-status returns cutaway's own code.
    for (const auto& [signal, code] : {std::pair{"INT", 130}, std::pair{"TERM", 143}}) {
        fs::remove_all(m_dir / "frames");
        CommandResult r = runCutaway("render " + scene.string(),
                                     std::string("timeout --preserve-status -s ") + signal + " 1");
        EXPECT_EQ(r.code, code) << signal << ": " << r.output;
        // timeout signals cutaway and then its process group: one request
        // arriving twice still ends in an orderly stop.
        EXPECT_NE(r.output.find("interrupted by signal"), std::string::npos) << r.output;
        const auto names = files(m_dir / "frames");
        ASSERT_LT(names.size(), 400u) << signal << ": the run was not interrupted";
        EXPECT_EQ(names, frameNames(0, static_cast<int>(names.size()) - 1))
            << signal << ": a gap or a stray file";
        for (const std::string& name : names) {
            Image img = readExr(m_dir / "frames" / name); // throws if truncated
            EXPECT_EQ(img.width, 96) << name;
        }
    }
}

TEST_F(CliTest, ASecondSignalEndsTheRunAtOnceLeavingNoTemporaries) {
    // Big frames of a tiny volume take long to write: the first signal comes
    // once a frame's temporary appears, the second 0.3 s later, while that
    // frame is still being written.
    const fs::path scene = write("long.json", turntable(399, 16, 2048));
    const std::string frames = (m_dir / "frames").string();
    const fs::path killer =
        write("killer.sh", "\"$@\" & pid=$!\n"
                           "while kill -0 $pid && ! ls -a " +
                               frames +
                               " 2>/dev/null | grep -q '[.]tmp-'; do\n"
                               "  sleep 0.01; done\n"
                               "kill -INT $pid; sleep 0.3; kill -INT $pid; wait $pid\n");
    CommandResult r = runCutaway("render " + scene.string(), "sh " + killer.string());
    EXPECT_EQ(r.code, 130) << r.output;
    const auto names = files(m_dir / "frames");
    ASSERT_LT(names.size(), 400u) << "the run was not interrupted";
    EXPECT_EQ(names, frameNames(0, static_cast<int>(names.size()) - 1)) << "a gap or a stray file";
    for (const std::string& name : names) {
        EXPECT_EQ(readExr(m_dir / "frames" / name).width, 2048) << name;
    }
}

namespace {

// A sequence of 20 96^2 frames, each an EXR and its PNG preview, written to
// a 40 KiB tmpfs that holds a few of them (mounted in a user and mount
// namespace of its own, so no root is needed) with `writers` frames written
// at once. Returns the run and the names left on the disk (empty when the
// namespaces are not available).
struct FullDiskRun {
    CommandResult result;
    std::vector<std::string> exrs, previews;
    bool available = false;
};

FullDiskRun runOnAFullDisk(const fs::path& dir, const fs::path& scene, int writers) {
    FullDiskRun run;
    if (runProgram("unshare", "-rm true").code != 0) return run;
    run.available = true;
    const fs::path disk = dir / "disk", kept = dir / "kept";
    fs::create_directories(disk);
    fs::create_directories(kept);
    // The tmpfs vanishes with the namespace: its files are copied out first.
    const std::string script = "mount -t tmpfs -o size=40k tmpfs " + disk.string() + " && " +
                               CUTAWAY_BINARY + " render " + scene.string() + " -o " +
                               (disk / "t_####.exr").string() + " --png --writers " +
                               std::to_string(writers) + "; rc=$?; cp -a " + disk.string() + "/. " +
                               kept.string() + "; exit $rc";
    run.result = runProgram("unshare", "-rm sh -c '" + script + "'");
    for (const auto& entry : fs::directory_iterator(kept)) {
        const fs::path name = entry.path().filename();
        (name.extension() == ".png" ? run.previews : run.exrs).push_back(name.string());
        if (name.extension() == ".exr") {
            EXPECT_EQ(readExr(entry.path()).width, 96) << name;
        }
    }
    std::sort(run.exrs.begin(), run.exrs.end());
    std::sort(run.previews.begin(), run.previews.end());
    // Both files of a frame or neither; nothing else (no temporaries).
    std::vector<std::string> expected;
    for (const std::string& name : run.exrs)
        expected.push_back(fs::path(name).replace_extension(".png").string());
    EXPECT_EQ(run.previews, expected) << "a preview without its EXR, or the reverse";
    const CommandResult& r = run.result;
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("No space left on device"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("stopped: a frame could not be written"), std::string::npos)
        << r.output;
    EXPECT_GE(run.exrs.size(), 1u) << r.output;
    EXPECT_LT(run.exrs.size(), 20u) << "the disk did not fill up";
    return run;
}

} // namespace

TEST_F(CliTest, AFullDiskStopsTheRunKeepingFinishedFramesWhole) {
    const fs::path scene = write("turn.json", turntable(19, 24, 96));
    const FullDiskRun run = runOnAFullDisk(m_dir, scene, 1);
    if (!run.available)
        GTEST_SKIP() << "needs unshare -rm (user and mount namespaces) to mount a small tmpfs";
    const std::vector<std::string>& names = run.exrs;
    const std::string& output = run.result.output;
    EXPECT_EQ(names, frameNames(0, static_cast<int>(names.size()) - 1)) << "a gap or a stray file";
    // One frame written at a time: the run stopped at the frame that did not
    // fit, and only that one failed.
    const std::string failed = "frame " + std::to_string(names.size()) + " failed";
    EXPECT_NE(output.find(failed), std::string::npos) << output;
    EXPECT_EQ(output.find("frame " + std::to_string(names.size() + 1) + " failed"),
              std::string::npos)
        << output;
}

// Frames written at once when the disk fills: every frame before the first
// that failed is whole, each failure is reported, and what finished after
// it is whole too (it was already being written).
TEST_F(CliTest, AFullDiskWithFramesWrittenAtOnceLeavesOnlyWholeFrames) {
    const fs::path scene = write("turn.json", turntable(19, 24, 96));
    const FullDiskRun run = runOnAFullDisk(m_dir, scene, 3);
    if (!run.available)
        GTEST_SKIP() << "needs unshare -rm (user and mount namespaces) to mount a small tmpfs";
    const std::string& output = run.result.output;
    const std::size_t firstFailed = output.find(" failed");
    ASSERT_NE(firstFailed, std::string::npos) << output;
    const std::size_t at = output.rfind("frame ", firstFailed);
    ASSERT_NE(at, std::string::npos) << output;
    const int first = std::stoi(output.substr(at + 6));
    const std::vector<std::string> before = frameNames(0, first - 1);
    ASSERT_LE(before.size(), run.exrs.size()) << output;
    EXPECT_TRUE(std::equal(before.begin(), before.end(), run.exrs.begin()))
        << "a frame before the first failure is missing";
    EXPECT_FALSE(std::count(run.exrs.begin(), run.exrs.end(), frameNames(first, first)[0]));
    // At most the two frames being written beside it may have finished after it.
    for (const std::string& name : run.exrs)
        EXPECT_LE(name, frameNames(first + 2, first + 2)[0]) << name << " rendered after the stop";
}

// A frame whose preview cannot be written leaves no EXR either: its files
// are both there or neither, so --skip-existing renders it again. (The
// preview's path is a link into a folder that does not exist.) One frame is
// written at a time, so the failure also stops the run before frame 2 (with
// several at once, frame 2 may already be on its way: the full-disk tests).
TEST_F(CliTest, AFrameWhosePreviewFailsLeavesNoExr) {
    const fs::path scene = write("turn.json", turntable());
    fs::create_symlink(m_dir / "nowhere" / "t.png", m_dir / "t_0001.png");
    CommandResult r =
        runCutaway("render " + scene.string() + " --frames 0..2 --png --writers 1 -o " +
                   (m_dir / "t_####.exr").string());
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("frame 1 failed"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("t_0001.png"), std::string::npos) << r.output;
    EXPECT_EQ(files(m_dir),
              (std::vector<std::string>{"t_0000.exr", "t_0000.png", "t_0001.png", "turn.json"}));
}

TEST_F(CliTest, AFailedFrameDoesNotStopTheOthersUnlessFailFast) {
    // fov leaves its range (0, 170) after frame 3.
    const fs::path scene = write("fov.json", R"({ "version": 1,
      "volume": { "phantom": "head", "size": [16, 16, 16] },
      "render": { "size": [16, 16] },
      "animation": { "frames": [0, 5], "tracks": [ { "target": "/camera/fov",
        "keys": [ { "frame": 0, "value": 100 }, { "frame": 5, "value": 200 } ] } ] },
      "output": { "pattern": "frames/t_####.exr" } })");
    CommandResult r = runCutaway("render " + scene.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("frame 4 failed"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(frame 4): /camera/fov"), std::string::npos) << r.output;
    // The file is named once, though its absolute path starts like a pointer.
    const std::string line = r.output.substr(r.output.find("frame 4 failed"));
    const std::string once = line.substr(0, line.find('\n'));
    EXPECT_EQ(once.find(scene.string()), once.rfind(scene.string())) << once;
    EXPECT_EQ(files(m_dir / "frames"), frameNames(0, 3));

    fs::remove_all(m_dir / "frames");
    CommandResult fast = runCutaway("render " + scene.string() + " --frames 3..5 --fail-fast");
    EXPECT_EQ(fast.code, 2) << fast.output;
    EXPECT_EQ(fast.output.find("frame 5 failed"), std::string::npos) << fast.output;
    EXPECT_EQ(files(m_dir / "frames"), frameNames(3, 3));
}

// /output/compression reaches the file; the pixels do not depend on it.
TEST_F(CliTest, TheSceneChoosesTheExrCompression) {
    std::string text = turntable(0);
    const std::string pattern = R"("pattern": "frames/t_####.exr")";
    const fs::path zip = write("zip.json", text);
    text.replace(text.find(pattern), pattern.size(),
                 R"("pattern": "none/t_####.exr", "compression": "none")");
    const fs::path none = write("none.json", text);
    ASSERT_EQ(runCutaway("render " + zip.string()).code, 0);
    ASSERT_EQ(runCutaway("render " + none.string()).code, 0);
    const fs::path zipped = m_dir / "frames" / "t_0000.exr", plain = m_dir / "none" / "t_0000.exr";
    EXPECT_EQ(exrCompressionCode(zipped), 3); // ZIP, the default
    EXPECT_EQ(exrCompressionCode(plain), 0);
    EXPECT_EQ(readExr(zipped).rgba, readExr(plain).rgba);
    EXPECT_LT(fs::file_size(zipped), fs::file_size(plain));
}

TEST_F(CliTest, SetOverridesAValueByPointer) {
    const fs::path scene = write("turn.json", turntable());
    CommandResult r =
        runCutaway("render " + scene.string() +
                   " --frames 0 --set /render/size=[20,10] --set /lights/ambient=0.5");
    ASSERT_EQ(r.code, 0) << r.output;
    const fs::path f0 = m_dir / "frames" / "t_0000.exr";
    EXPECT_EQ(readExr(f0).width, 20);
    EXPECT_DOUBLE_EQ(
        nlohmann::json::parse(readExrStringAttribute(f0, "cutaway/scene"))["lights"]["ambient"]
            .get<double>(),
        0.5);
    CommandResult bad = runCutaway("render " + scene.string() + " --set /render/size/0=-3");
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.output.find("/render/size/0"), std::string::npos) << bad.output;
    EXPECT_EQ(runCutaway("render " + scene.string() + " --set render=1").code, 2);
}

TEST_F(CliTest, ValidateChecksEveryFrame) {
    const fs::path scene = write("fov.json", R"({ "version": 1,
      "volume": { "phantom": "head" },
      "animation": { "frames": [0, 5], "tracks": [ { "target": "/camera/fov",
        "keys": [ { "frame": 0, "value": 100 }, { "frame": 5, "value": 200 } ] } ] } })");
    CommandResult r = runCutaway("validate " + scene.string());
    EXPECT_EQ(r.code, 2) << r.output;
    // Both failing frames, not only the first.
    EXPECT_NE(r.output.find("(frame 4): /camera/fov"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(frame 5): /camera/fov"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("(frame 3)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("2 of 6 frames are not valid"), std::string::npos) << r.output;
}

// Every scene in scenes/ renders at a small size (real scans: skipped when
// absent), in four tests of every fourth scene by name, which ctest runs side
// by side (one test took 3 minutes of the sanitizer run alone).
void renderEveryFourthExample(const fs::path& dir, std::size_t part) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(fs::path(CUTAWAY_SOURCE_DIR) / "scenes")) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() == ".json" && name.find(".schema.") == std::string::npos)
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    ASSERT_GE(files.size(), 8u);
    for (std::size_t i = part; i < files.size(); i += 4) {
        const std::string name = files[i].filename().string();
        SCOPED_TRACE(name);
        const std::string text = [&] {
            std::ifstream in(files[i]);
            return std::string(std::istreambuf_iterator<char>(in), {});
        }();
        if (text.find("shared/data") != std::string::npos && !fs::exists(CUTAWAY_SHARED_DATA)) {
            std::printf("skipped %s: %s not found\n", name.c_str(), CUTAWAY_SHARED_DATA);
            continue;
        }
        // A series scripts/write_dicom.py writes (tests/cli/dicom_cli_test.cpp renders it).
        if (text.find("out/dicom/") != std::string::npos) {
            std::printf("skipped %s: its DICOM series is written by scripts/write_dicom.py\n",
                        name.c_str());
            continue;
        }
        const fs::path out = dir / (files[i].stem().string() + "_####.exr");
        CommandResult r = runCutaway("render " + files[i].string() +
                                     " --size 40x32 --frames 0 -o " + out.string());
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_EQ(readExr(job::expandPattern(out.string(), 0)).width, 40);
    }
}

TEST_F(CliTest, EveryExampleSceneRendersSmall0) {
    renderEveryFourthExample(m_dir, 0);
}
TEST_F(CliTest, EveryExampleSceneRendersSmall1) {
    renderEveryFourthExample(m_dir, 1);
}
TEST_F(CliTest, EveryExampleSceneRendersSmall2) {
    renderEveryFourthExample(m_dir, 2);
}
TEST_F(CliTest, EveryExampleSceneRendersSmall3) {
    renderEveryFourthExample(m_dir, 3);
}

// The bad-scene corpus through the binary: exit 2, the file and a location named.
TEST_F(CliTest, EveryBadSceneExitsTwoNamingItsLocation) {
    const fs::path bad = fs::path(CUTAWAY_SOURCE_DIR) / "tests" / "scene" / "bad";
    int count = 0;
    for (const auto& entry : fs::directory_iterator(bad)) {
        SCOPED_TRACE(entry.path().filename().string());
        CommandResult r = runCutaway("validate " + entry.path().string());
        EXPECT_EQ(r.code, 2) << r.output;
        EXPECT_NE(r.output.find(entry.path().filename().string()), std::string::npos) << r.output;
        const bool located = r.output.find(": /") != std::string::npos ||
                             r.output.find(": (root)") != std::string::npos ||
                             r.output.find(".json:") != std::string::npos;
        EXPECT_TRUE(located) << r.output;
        // render refuses it the same way, before writing anything.
        const fs::path out = m_dir / "out";
        CommandResult render =
            runCutaway("render " + entry.path().string() + " -o " + (out / "f_####.exr").string());
        EXPECT_EQ(render.code, 2) << render.output;
        EXPECT_FALSE(fs::exists(out)) << "render wrote something";
        ++count;
    }
    EXPECT_GE(count, 53);
}

} // namespace cutaway::test

namespace cutaway::test {

TEST_F(CliTest, OperatorIdChannelIsWrittenOnRequest) {
    const fs::path scene = write("op.json", R"({ "version": 1,
      "volume": { "phantom": "head", "size": [24, 24, 24] },
      "render": { "size": [20, 16] },
      "operators": [ { "type": "retractor", "placement": { "translate": [0, 0, 6], "scale": [16, 20, 12] } } ],
      "output": { "pattern": "frames/t_####.exr" } })");
    ASSERT_EQ(runCutaway("render " + scene.string()).code, 0);
    EXPECT_THROW(readExrChannel(m_dir / "frames" / "t_0000.exr", "operator_id"), InputError);
    CommandResult r = runCutaway("render " + scene.string() + " --set /output/operator_id=true");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto ids = readExrChannel(m_dir / "frames" / "t_0000.exr", "operator_id");
    ASSERT_EQ(ids.size(), 20u * 16u);
    EXPECT_NE(std::find(ids.begin(), ids.end(), 0.0f), ids.end()) << "the retractor is visible";
    EXPECT_EQ(ids[0], -2.0f) << "a corner sees nothing";
}

} // namespace cutaway::test
