#include "io/atomic_file.hpp"

#include "core/error.hpp"
#include "io/input_file.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

namespace cutaway {

namespace {

namespace fs = std::filesystem;

// Distinguishes temporaries of concurrent calls within one process; the host
// and the pid distinguish processes writing into the same folder.
std::atomic<unsigned long> g_tmpCounter{0};

// This host's name as temporaries carry it (atomic_file.hpp).
const std::string& hostName() {
    static const std::string name = [] {
        char buffer[256] = {};
        if (::gethostname(buffer, sizeof buffer - 1) != 0 || buffer[0] == '\0')
            return std::string("localhost");
        std::string host(buffer, ::strnlen(buffer, kLongestHostName));
        for (char& c : host)
            if (c == '/' || static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '_';
        return host;
    }();
    return name;
}

fs::path temporaryPathFor(const fs::path& target) {
    // Built by appending: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
    std::string name = ".";
    name += target.filename().string();
    name += ".tmp-";
    name += hostName();
    name += '-';
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
    throw InputError("cannot write " + printable(path.string()) +
                     ": too many levels of symbolic links");
}

void checkReplaceable(const fs::path& target, const fs::path& requested) {
    struct stat status {};
    if (::stat(target.c_str(), &status) != 0 || S_ISREG(status.st_mode)) return;
    throw InputError("cannot write " + printable(requested.string()) + ": it exists and is " +
                     nonRegularKind(status.st_mode) +
                     ", which cutaway does not replace; name a regular file");
}

// What the system would refuse about the path to the folder `target` goes
// in, found before anything renders: a link loop, a name too long. A folder
// that does not exist yet is made by the writer (and a file in its way is
// the writer's RuntimeError, as a read-only folder is).
void checkFolderOf(const fs::path& target, const fs::path& requested) {
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    struct stat status {};
    if (::stat(folder.c_str(), &status) == 0) return;
    const int err = errno;
    if (err == ELOOP || err == ENAMETOOLONG)
        throw InputError("cannot write " + printable(requested.string()) + ": folder " +
                         printable(folder.string()) + ": " + std::strerror(err));
}

} // namespace

std::string printable(std::string_view text) {
    static const char* kHex = "0123456789abcdef";
    std::string out;
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte != 0x7F) {
            out += c;
            continue;
        }
        out += "\\x";
        out += kHex[byte >> 4];
        out += kHex[byte & 15];
    }
    return out;
}

fs::path writeTarget(const fs::path& requested) {
    const std::string& text = requested.native();
    constexpr std::size_t kLongestShown = 300; // of a path too long to write
    const std::string shown = text.size() > kLongestShown
                                  ? printable(text.substr(0, kLongestShown)) + "..."
                                  : printable(text);
    const fs::path name = requested.filename();
    if (name.empty() || name == "." || name == "..")
        throw InputError("cannot write " + shown + ": the path names a folder, not a file");
    const auto control = [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7F; };
    if (std::any_of(text.begin(), text.end(), control))
        throw InputError("cannot write " + shown +
                         ": the path holds a control character (shown as \\xNN)");
    const fs::path target = followLinks(requested);
    // The temporary's name must fit too: it is the longest path written.
    const std::size_t extra = 1 + 5 + kLongestHostName + 1 + 7 + 1 + 20;
    if (target.filename().string().size() > kLongestFileName)
        throw InputError("cannot write " + shown + ": the file name is longer than the " +
                         std::to_string(kLongestFileName) +
                         " bytes cutaway can write (a folder holds names of 255, and each "
                         "file is first written under a longer temporary name)");
    for (const fs::path& path : {requested, target}) {
        if (path.native().size() + extra >= PATH_MAX)
            throw InputError("cannot write " + shown + ": the path is longer than the " +
                             std::to_string(PATH_MAX - 1 - extra) +
                             " bytes cutaway can write (PATH_MAX, with the temporary's name)");
    }
    checkFolderOf(target, requested);
    checkReplaceable(target, requested);
    return target;
}

void removeTemporariesNow() noexcept {
    for (Slot& slot : g_slots) {
        if (slot.state.load() == kReady) (void)::unlink(slot.path);
    }
}

void writeAtomically(const fs::path& requested,
                     const std::function<void(const fs::path& tmp)>& write) {
    const fs::path target = writeTarget(requested);
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

namespace {

bool allDigits(std::string_view text) {
    return !text.empty() &&
           std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The pid of `file` when it is a temporary of one of `names` written on this
// host (".NAME.tmp-HOST-PID-N"), else 0.
long temporaryWriter(const std::string& file, const std::set<std::string>& names) {
    const std::string marker = ".tmp-" + hostName() + "-";
    const std::size_t at = file.rfind(marker);
    if (file.size() < 2 || file[0] != '.' || at == std::string::npos || at < 2) return 0;
    if (!names.contains(file.substr(1, at - 1))) return 0;
    const std::string_view rest = std::string_view(file).substr(at + marker.size());
    const std::size_t dash = rest.find('-');
    if (dash == std::string_view::npos || dash > 7) return 0;
    const std::string_view pid = rest.substr(0, dash);
    if (!allDigits(pid) || !allDigits(rest.substr(dash + 1))) return 0;
    return std::stol(std::string(pid));
}

} // namespace

std::vector<fs::path> removeStaleTemporaries(const fs::path& folder,
                                             const std::set<std::string>& names) {
    std::vector<fs::path> removed;
    std::error_code ec;
    const fs::path where = folder.empty() ? fs::path(".") : folder;
    for (fs::directory_iterator it(where, ec), end; !ec && it != end; it.increment(ec)) {
        const long pid = temporaryWriter(it->path().filename().string(), names);
        // Its writer provably gone: no process of that pid on this host.
        if (pid <= 0 || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
        std::error_code status;
        if (!fs::is_regular_file(fs::symlink_status(it->path(), status))) continue;
        if (::unlink(it->path().c_str()) == 0) removed.push_back(it->path());
    }
    return removed;
}

} // namespace cutaway
