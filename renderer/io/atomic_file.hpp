#pragma once
// Writes a file so that readers never see a partial one: the content goes to a
// temporary name in the same folder (same file system), then is renamed over
// the target. If writing throws, the temporary is removed and the target is
// left as it was. A target that is a symbolic link is written through (the
// file it names is replaced, the link stays); one that exists and is not a
// regular file (a folder, a device such as /dev/null, a named pipe) is
// refused, since the rename would replace it with a regular file.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace cutaway {

/// A temporary's name is ".NAME.tmp-HOST-PID-N": the target's name, the
/// host and the process that writes it (shards of one sequence run on many
/// hosts over one shared file system, each process numbering its own from
/// 0), so that a temporary left by a killed process can be told from one
/// being written (removeStaleTemporaries). HOST is the host name (at most
/// 64 bytes on Linux; a '/' or a control character in it becomes '_').
inline constexpr std::size_t kLongestHostName = 64;

/// The longest file name writeAtomically() takes: its temporary's name adds
/// "." and ".tmp-HOST-PID-N" (a host name of at most 64 bytes, a Linux pid
/// of at most 7 digits, N of at most 20) and must still fit the 255 bytes a
/// folder entry holds on Linux file systems.
inline constexpr std::size_t kLongestFileName = 255 - (1 + 5 + kLongestHostName + 1 + 7 + 1 + 20);

/// `text` with every control character written as \xNN, for messages.
std::string printable(std::string_view text);

/// The file writeAtomically(requested) writes: `requested`, or the file a
/// symbolic link there names. Throws InputError "cannot write REQUESTED:
/// ..." when the path names no file (it ends in a slash, "." or ".."), holds
/// a control character, is longer than the system takes (PATH_MAX with the
/// temporary's name; a file name past kLongestFileName), its links loop, a
/// folder on its way is not one, or it exists and is not a regular file.
/// Render and validate check output paths with it before anything renders.
std::filesystem::path writeTarget(const std::filesystem::path& requested);

/// Calls write(tmp) with a temporary path next to `target`, then renames it to
/// `target`. Throws InputError naming the target when writeTarget refuses it,
/// RuntimeError when the folder is not writable or the rename fails;
/// rethrows whatever write() throws, after removing the temporary.
void writeAtomically(const std::filesystem::path& target,
                     const std::function<void(const std::filesystem::path& tmp)>& write);

/// writeAtomically() calls whose temporaries removeTemporariesNow() knows of
/// at once; more concurrent writes than this go unregistered.
inline constexpr int kTrackedTemporaries = 32;

/// Unlinks the temporaries of every writeAtomically() call in flight.
/// Async-signal-safe (only atomics and unlink): a signal handler that is about
/// to end the process calls it so that no temporary outlives the process.
/// The writes it interrupts then fail, so call it only on the way out.
void removeTemporariesNow() noexcept;

/// Removes the temporaries of `names` (files of `folder`, as writeTarget
/// gives them) that a killed process left: only those written on this host
/// by a process that is gone (kill(pid, 0) fails with ESRCH). Another host's
/// temporaries (a shared file system), a live process's and files of other
/// names are never touched. Returns the paths removed.
std::vector<std::filesystem::path> removeStaleTemporaries(const std::filesystem::path& folder,
                                                          const std::set<std::string>& names);

} // namespace cutaway
