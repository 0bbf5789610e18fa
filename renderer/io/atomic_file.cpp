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
// published slots. More concurrent writes than slots go unregistered (the
// sequence writer has at most two in flight).
enum SlotState : int { kFree, kFilling, kReady };
struct Slot {
    std::atomic<int> state{kFree};
    char path[PATH_MAX];
};
std::array<Slot, 8> g_slots;
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

} // namespace

void removeTemporariesNow() noexcept {
    for (Slot& slot : g_slots) {
        if (slot.state.load() == kReady) (void)::unlink(slot.path);
    }
}

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
        throw RuntimeError("cannot write " + target.string() + ": renaming " + tmp.string() +
                           " over it failed (" + ec.message() + ")");
    }
}

} // namespace cutaway
