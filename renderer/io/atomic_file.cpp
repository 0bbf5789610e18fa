#include "io/atomic_file.hpp"

#include "core/error.hpp"

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
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

// The temporaries being written, for removeTemporariesNow(), which may run in
// a signal handler: fixed storage, no locks. A slot is claimed (kFree ->
// kFilling), its path copied, then published (kReady); the handler reads only
// published slots. More concurrent writes than slots go unregistered (a
// sequence writes at most job::kMostWritersAllowed frames at once, each
// file after the other).
enum SlotState : int { kFree, kFilling, kReady };
struct Slot {
    std::atomic<int> state{kFree};
    char path[PATH_MAX];
};
std::array<Slot, kTrackedTemporaries> g_slots;
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

class Registered {
public:
    explicit Registered(const fs::path& tmp) {
        const std::string& text = tmp.native();
        if (text.size() >= PATH_MAX) return;
        for (Slot& slot : g_slots) {
            int expected = kFree;
            if (slot.state.compare_exchange_strong(expected, kFilling)) {
                std::memcpy(slot.path, text.c_str(), text.size() + 1);
                slot.state.store(kReady);
                m_slot = &slot;
                return;
            }
        }
    }
    ~Registered() {
        if (m_slot != nullptr) m_slot->state.store(kFree);
    }
    Registered(const Registered&) = delete;
    Registered& operator=(const Registered&) = delete;

private:
    Slot* m_slot = nullptr;
};

// A link is written through: the file it names is replaced (or made, for a
// link to a file not written yet), the link stays. Gives up on a loop.
fs::path followLinks(const fs::path& path) {
    fs::path p = path;
    for (int hops = 0; hops < 40; ++hops) {
        std::error_code ec;
        if (!fs::is_symlink(fs::symlink_status(p, ec))) return p;
        const fs::path next = fs::read_symlink(p, ec);
        if (ec) return p;
        p = (next.is_absolute() ? next : p.parent_path() / next).lexically_normal();
    }
    throw InputError("cannot write " + path.string() + ": too many levels of symbolic links");
}

void checkReplaceable(const fs::path& target, const fs::path& requested) {
    std::error_code ec;
    const fs::file_status status = fs::status(target, ec);
    if (ec || !fs::exists(status) || fs::is_regular_file(status)) return;
    const char* what = fs::is_directory(status)        ? "a folder"
                       : fs::is_character_file(status) ? "a character device"
                       : fs::is_block_file(status)     ? "a block device"
                       : fs::is_fifo(status)           ? "a named pipe"
                       : fs::is_socket(status)         ? "a socket"
                                                       : "not a regular file";
    throw InputError("cannot write " + requested.string() + ": it exists and is " + what +
                     ", which cutaway does not replace; name a regular file");
}

} // namespace

void removeTemporariesNow() noexcept {
    for (Slot& slot : g_slots) {
        if (slot.state.load() == kReady) (void)::unlink(slot.path);
    }
}

void writeAtomically(const fs::path& requested,
                     const std::function<void(const fs::path& tmp)>& write) {
    if (requested.filename().empty()) {
        throw RuntimeError("cannot write " + requested.string() + ": the path names no file");
    }
    const fs::path target = followLinks(requested);
    checkReplaceable(target, requested);
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    // Checked up front so the message names the folder rather than whatever
    // the writer (OpenEXR, an ofstream) reports about the temporary name.
    if (::access(folder.c_str(), W_OK | X_OK) != 0) {
        const int err = errno;
        throw RuntimeError("cannot write " + requested.string() + ": folder " + folder.string() +
                           " is not writable (" + std::strerror(err) + ")");
    }

    const fs::path tmp = temporaryPathFor(target);
    const Registered registered(tmp);
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
        throw RuntimeError("cannot write " + requested.string() + ": renaming " + tmp.string() +
                           " over it failed (" + ec.message() + ")");
    }
}

} // namespace cutaway
