#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "temp_dir.hpp"

#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <unistd.h>

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

TEST(AtomicFile, FailedRenameThrowsAndRemovesTheTemporary) {
    TempDir dir;
    const fs::path target = dir / "taken";
    fs::create_directories(target / "child"); // a non-empty folder cannot be renamed over
    try {
        writeAtomically(target, [&](const fs::path& tmp) { writeText(tmp, "data"); });
        FAIL() << "expected RuntimeError";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    }
    EXPECT_EQ(dir.list(), std::vector<std::string>{"taken"});
    EXPECT_TRUE(fs::is_directory(target / "child"));
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
