#include "io/atomic_file.hpp"

#include "core/error.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <system_error>
#include <unistd.h>

namespace cutaway {

namespace {

namespace fs = std::filesystem;

// Distinguishes temporaries of concurrent calls within one process; the pid
// distinguishes processes writing into the same folder.
std::atomic<unsigned long> g_tmpCounter{0};

fs::path temporaryPathFor(const fs::path& target) {
    // Built by appending: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
    std::string name = ".";
    name += target.filename().string();
    name += ".tmp-";
    name += std::to_string(static_cast<long>(::getpid()));
    name += '-';
    name += std::to_string(g_tmpCounter.fetch_add(1));
    return target.parent_path() / name;
}

// Flushes the temporary's data to disk before the rename, so that after a
// crash the target is either the old file or the complete new one, never an
// empty file with the new name. Best effort: a file system without fsync
// (some network mounts) still gets the rename.
void syncFile(const fs::path& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    (void)::fsync(fd);
    (void)::close(fd);
}

void removeQuietly(const fs::path& path) {
    std::error_code ignored;
    fs::remove(path, ignored);
}

} // namespace

void writeAtomically(const fs::path& target,
                     const std::function<void(const fs::path& tmp)>& write) {
    if (target.filename().empty()) {
        throw RuntimeError("cannot write " + target.string() + ": the path names no file");
    }
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    // Checked up front so the message names the folder rather than whatever
    // the writer (OpenEXR, an ofstream) reports about the temporary name.
    if (::access(folder.c_str(), W_OK | X_OK) != 0) {
        const int err = errno;
        throw RuntimeError("cannot write " + target.string() + ": folder " + folder.string() +
                           " is not writable (" + std::strerror(err) + ")");
    }

    const fs::path tmp = temporaryPathFor(target);
    try {
        write(tmp);
    } catch (...) {
        removeQuietly(tmp);
        throw;
    }
    syncFile(tmp);

    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) {
        removeQuietly(tmp);
        throw RuntimeError("cannot write " + target.string() + ": renaming " + tmp.string() +
                           " over it failed (" + ec.message() + ")");
    }
}

} // namespace cutaway
