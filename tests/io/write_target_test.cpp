// What writeAtomically() refuses before it writes (writeTarget: the check
// render and validate share), what its temporaries are named, and which of
// them removeStaleTemporaries() may remove.
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/input_file.hpp"
#include "temp_dir.hpp"

#include <climits>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace cutaway {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

std::string refusal(const fs::path& path) {
    try {
        writeTarget(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::string host() {
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    return name;
}

// A pid that belonged to a process that has ended (and been waited for).
long goneProcess() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);
    return child;
}

void touch(const fs::path& path) {
    std::ofstream(path) << "partial";
}

TEST(WriteTarget, PathsNoWriteCouldSucceedAreRefusedUpFront) {
    TempDir dir;
    // A folder, not a file: "newdir/" was refused only once the frame was rendered.
    for (const fs::path& path : {dir / "newdir/", dir / ".", dir / "..", fs::path("")})
        EXPECT_NE(refusal(path).find("the path names a folder, not a file"), std::string::npos)
            << path;
    // A control character: the system would cut the name at a NUL.
    const std::string nul = (dir / "shot").string() + std::string(1, '\0') + "_0001.exr";
    EXPECT_EQ(refusal(nul), "cannot write " + (dir / "shot").string() +
                                "\\x00_0001.exr: the path holds a control character (shown as "
                                "\\xNN)");
    EXPECT_NE(refusal(dir / "a\nb.exr").find("a\\x0ab.exr: the path holds a control character"),
              std::string::npos);
    // Longer than PATH_MAX (with the temporary's name).
    std::string deep = dir.path().string();
    while (deep.size() < PATH_MAX)
        deep += "/abcdefgh";
    EXPECT_NE(refusal(deep + "/f.exr").find("bytes cutaway can write (PATH_MAX"),
              std::string::npos);
    // A name a folder entry cannot hold with the temporary's additions.
    EXPECT_NE(refusal(dir / std::string(kLongestFileName + 1, 'n')).find("file name is longer"),
              std::string::npos);
    EXPECT_EQ(refusal(dir / std::string(kLongestFileName, 'n')), "");
    // Links that loop, as the file or on the way to its folder.
    fs::create_symlink(dir / "loop1", dir / "loop2");
    fs::create_symlink(dir / "loop2", dir / "loop1");
    EXPECT_NE(refusal(dir / "loop1").find("too many levels of symbolic links"), std::string::npos);
    EXPECT_NE(refusal(dir / "loop1" / "f.exr").find("Too many levels of symbolic links"),
              std::string::npos);
    // A file where a folder must be is left to the writer: a runtime error,
    // as a read-only folder is.
    std::ofstream(dir / "file") << "x";
    EXPECT_EQ(refusal(dir / "file" / "f.exr"), "");
    EXPECT_THROW(writeAtomically(dir / "file" / "f.exr", [](const fs::path&) {}), RuntimeError);
    // The controls: a new file in a folder that does not exist yet, an existing file.
    EXPECT_EQ(refusal(dir / "new" / "deeper" / "f.exr"), "");
    EXPECT_EQ(writeTarget(dir / "file"), dir / "file");
    // writeAtomically refuses the same paths, before calling its writer.
    bool called = false;
    EXPECT_THROW(writeAtomically(dir / "newdir/", [&](const fs::path&) { called = true; }),
                 InputError);
    EXPECT_FALSE(called);
}

TEST(WriteTarget, TemporariesCarryTheHostAndTheProcess) {
    TempDir dir;
    fs::path seen;
    writeAtomically(dir / "f.exr", [&](const fs::path& tmp) {
        seen = tmp;
        std::ofstream(tmp) << "x";
    });
    const std::string prefix = ".f.exr.tmp-" + host() + "-" + std::to_string(::getpid()) + "-";
    EXPECT_EQ(seen.filename().string().rfind(prefix, 0), 0u) << seen;
    EXPECT_EQ(seen.parent_path(), dir.path());
}

TEST(WriteTarget, OnlyThisHostsTemporariesOfGoneProcessesAreRemoved) {
    TempDir dir;
    const std::string me = host();
    const std::string dead = std::to_string(goneProcess());
    const std::string live = std::to_string(::getpid());
    const std::vector<std::string> stale = {".f_0000.exr.tmp-" + me + "-" + dead + "-0",
                                            ".f_0000.png.tmp-" + me + "-" + dead + "-7"};
    const std::vector<std::string> kept = {
        ".f_0000.exr.tmp-" + me + "-" + live + "-0",       // being written
        ".f_0000.exr.tmp-other" + me + "-" + dead + "-0",  // another host's
        ".f_0000.exr.tmp-" + me + ".other-" + dead + "-0", // another host's
        ".f_0001.exr.tmp-" + me + "-" + dead + "-0",       // not a frame of this run
        ".f_0000.exr.tmp-" + me + "-" + dead + "-x",       // not cutaway's naming
        ".f_0000.exr.tmp-" + me + "-" + dead,              // not cutaway's naming
        "f_0000.exr.tmp-" + me + "-" + dead + "-0",        // not cutaway's naming
    };
    for (const auto& names : {stale, kept})
        for (const std::string& name : names)
            touch(dir / name);
    fs::create_directories(dir / (".f_0000.exr.tmp-" + me + "-" + dead + "-1")); // a folder
    const std::vector<fs::path> removed =
        removeStaleTemporaries(dir.path(), {"f_0000.exr", "f_0000.png"});
    EXPECT_EQ(removed.size(), 2u);
    for (const std::string& name : stale)
        EXPECT_FALSE(fs::exists(dir / name)) << name;
    for (const std::string& name : kept)
        EXPECT_TRUE(fs::exists(dir / name)) << name;
    EXPECT_TRUE(fs::is_directory(dir / (".f_0000.exr.tmp-" + me + "-" + dead + "-1")));
}

TEST(WriteTarget, FilesAreComparedAsFilesNotAsText) {
    TempDir dir;
    std::ofstream(dir / "vol.nrrd") << "x";
    fs::create_directories(dir / "sub");
    fs::create_directory_symlink(dir / "sub", dir / "link");
    fs::create_symlink(dir / "vol.nrrd", dir / "vol_link.nrrd");
    // An existing file: by device and inode, whatever the spelling.
    const auto vol = fileIdOf(dir / "vol.nrrd");
    ASSERT_TRUE(vol);
    EXPECT_TRUE(vol->name.empty());
    EXPECT_EQ(fileIdOf(dir / "sub" / ".." / "vol.nrrd"), vol);
    EXPECT_EQ(fileIdOf(dir / "vol_link.nrrd"), vol);
    // A new file: its folder's device and inode and its name.
    EXPECT_EQ(fileIdOf(dir / "sub" / "new.nrrd"), fileIdOf(dir / "link" / "new.nrrd"));
    EXPECT_EQ(fileIdOf(dir / "sub" / "new.nrrd")->name, "new.nrrd");
    // The controls: other names, other folders.
    EXPECT_NE(fileIdOf(dir / "sub" / "new.nrrd"), fileIdOf(dir / "sub" / "other.nrrd"));
    EXPECT_NE(fileIdOf(dir / "sub" / "new.nrrd"), fileIdOf(dir / "new.nrrd"));
    EXPECT_FALSE(fileIdOf(dir / "none" / "new.nrrd"));
}

} // namespace
} // namespace cutaway
