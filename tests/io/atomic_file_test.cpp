#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "temp_dir.hpp"

#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>

namespace cutaway {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    ASSERT_TRUE(out.good()) << path;
}

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(AtomicFile, WritesTheTargetAndLeavesNoTemporary) {
    TempDir dir;
    const fs::path target = dir / "out.txt";
    fs::path seen;
    writeAtomically(target, [&](const fs::path& tmp) {
        seen = tmp;
        EXPECT_FALSE(fs::exists(target)); // not visible under its name while being written
        writeText(tmp, "hello");
    });
    EXPECT_EQ(readText(target), "hello");
    EXPECT_EQ(dir.list(), std::vector<std::string>{"out.txt"});
    // The temporary is hidden, in the same folder, and named after the target.
    EXPECT_EQ(seen.parent_path(), dir.path());
    EXPECT_EQ(seen.filename().string().rfind(".out.txt.tmp-", 0), 0u) << seen;
}

TEST(AtomicFile, TemporaryNamesAreUniquePerCall) {
    TempDir dir;
    std::set<fs::path> names;
    for (int i = 0; i < 5; ++i) {
        writeAtomically(dir / "out.txt", [&](const fs::path& tmp) {
            names.insert(tmp);
            writeText(tmp, std::to_string(i));
        });
    }
    EXPECT_EQ(names.size(), 5u);
    EXPECT_EQ(readText(dir / "out.txt"), "4");
}

TEST(AtomicFile, ReplacesAnExistingTarget) {
    TempDir dir;
    const fs::path target = dir / "frame.png";
    writeText(target, "old content, longer than the new");
    writeAtomically(target, [&](const fs::path& tmp) {
        EXPECT_EQ(readText(target), "old content, longer than the new"); // intact meanwhile
        writeText(tmp, "new");
    });
    EXPECT_EQ(readText(target), "new");
    EXPECT_EQ(dir.list(), std::vector<std::string>{"frame.png"});
}

TEST(AtomicFile, MissingFolderThrowsNamingItAndLeavesNothing) {
    TempDir dir;
    const fs::path folder = dir / "no-such-folder";
    bool called = false;
    try {
        writeAtomically(folder / "out.txt", [&](const fs::path&) { called = true; });
        FAIL() << "expected RuntimeError";
    } catch (const RuntimeError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(folder.string()), std::string::npos) << message;
        EXPECT_NE(message.find("not writable"), std::string::npos) << message;
    }
    EXPECT_FALSE(called);
    EXPECT_FALSE(fs::exists(folder));
    EXPECT_TRUE(dir.list().empty());
}

TEST(AtomicFile, ThrowingWriterLeavesNeitherTargetNorTemporary) {
    TempDir dir;
    const fs::path target = dir / "out.exr";
    EXPECT_THROW(writeAtomically(target,
                                 [&](const fs::path& tmp) {
                                     writeText(tmp, "partial");
                                     throw std::logic_error("writer failed");
                                 }),
                 std::logic_error); // rethrown unchanged
    EXPECT_TRUE(dir.list().empty());
}

TEST(AtomicFile, ThrowingWriterKeepsTheOldTarget) {
    TempDir dir;
    const fs::path target = dir / "out.exr";
    writeText(target, "previous frame");
    EXPECT_THROW(writeAtomically(target,
                                 [&](const fs::path& tmp) {
                                     writeText(tmp, "partial");
                                     throw RuntimeError("disk full");
                                 }),
                 RuntimeError);
    EXPECT_EQ(readText(target), "previous frame");
    EXPECT_EQ(dir.list(), std::vector<std::string>{"out.exr"});
}

TEST(AtomicFile, FailedRenameThrowsNamingTheTarget) {
    TempDir dir;
    const fs::path target = dir / "out.exr";
    try { // a writer that leaves no temporary: there is nothing to rename
        writeAtomically(target, [&](const fs::path&) {});
        FAIL() << "expected RuntimeError";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("renaming"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(dir.list().empty());
}

// The rename would put a regular file in place of whatever has the name: as
// root, `-o /dev/null` replaced the system's /dev/null. Such targets are
// refused before anything is written. (A named pipe stands in for a device
// here, so that a broken check cannot damage the machine running the test.)
TEST(AtomicFile, RefusesToReplaceWhatIsNotARegularFile) {
    TempDir dir;
    const fs::path folder = dir / "taken";
    fs::create_directories(folder / "child");
    const fs::path pipe = dir / "frame_0000.exr";
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    for (const auto& [target, what] : {std::pair{folder, "a folder"}, {pipe, "a named pipe"}}) {
        bool called = false;
        try {
            writeAtomically(target, [&](const fs::path& tmp) {
                called = true;
                writeText(tmp, "data");
            });
            ADD_FAILURE() << "expected InputError for " << target;
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(target.string()), std::string::npos) << message;
            EXPECT_NE(message.find(what), std::string::npos) << message;
        }
        EXPECT_FALSE(called) << target;
    }
    EXPECT_TRUE(fs::is_directory(folder / "child"));
    EXPECT_TRUE(fs::is_fifo(pipe));
    EXPECT_EQ(dir.list(), (std::vector<std::string>{"frame_0000.exr", "taken"}));
}

// A link is written through: the file it names gets the new content and the
// link stays a link (a link to a pipe is refused like the pipe).
TEST(AtomicFile, WritesThroughASymbolicLink) {
    TempDir dir;
    fs::create_directories(dir / "store");
    const fs::path real = dir / "store" / "frame.exr";
    writeText(real, "old");
    const fs::path link = dir / "frame.exr";
    fs::create_symlink(real, link);
    writeAtomically(link, [&](const fs::path& tmp) { writeText(tmp, "new"); });
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
    EXPECT_EQ(readText(real), "new");
    EXPECT_EQ(dir.list(), (std::vector<std::string>{"frame.exr", "store"}));

    const fs::path pipe = dir / "store" / "pipe";
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    fs::create_symlink(pipe, dir / "to_pipe.exr");
    EXPECT_THROW(
        writeAtomically(dir / "to_pipe.exr", [&](const fs::path& tmp) { writeText(tmp, "x"); }),
        InputError);
    EXPECT_TRUE(fs::is_fifo(pipe));
}

TEST(AtomicFile, TemporariesInFlightCanBeRemovedAtOnce) {
    // What the CLI's second-signal handler does before it ends the process:
    // every temporary being written disappears; the target never appears.
    TempDir dir;
    const fs::path target = dir / "frame.exr";
    EXPECT_THROW(writeAtomically(target,
                                 [&](const fs::path& tmp) {
                                     writeText(tmp, "half a frame");
                                     ASSERT_TRUE(fs::exists(tmp));
                                     removeTemporariesNow();
                                     EXPECT_FALSE(fs::exists(tmp));
                                 }),
                 RuntimeError);
    EXPECT_TRUE(dir.list().empty());
    // Finished writes are no longer registered: their targets stay.
    writeAtomically(target, [&](const fs::path& tmp) { writeText(tmp, "whole"); });
    removeTemporariesNow();
    EXPECT_EQ(readText(target), "whole");
}

TEST(AtomicFile, ReadOnlyFolderThrowsNamingIt) {
    if (::geteuid() == 0) GTEST_SKIP() << "root ignores folder permissions";
    TempDir dir;
    const fs::path folder = dir / "read-only";
    fs::create_directories(folder);
    fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec);
    bool called = false;
    try {
        writeAtomically(folder / "out.txt", [&](const fs::path&) { called = true; });
        ADD_FAILURE() << "expected RuntimeError";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(folder.string()), std::string::npos) << e.what();
    }
    fs::permissions(folder, fs::perms::owner_all);
    EXPECT_FALSE(called);
    EXPECT_TRUE(fs::is_empty(folder));
}

} // namespace
} // namespace cutaway
