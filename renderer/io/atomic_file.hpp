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
#include <string>
#include <string_view>
#include <vector>

namespace cutaway {

/// The longest file name writeAtomically() takes: the temporary's name adds
/// "." and ".tmp-PID-N" (a Linux pid has at most 7 digits, N at most 20) and
/// must still fit the 255 bytes a folder entry holds on Linux file systems.
inline constexpr std::size_t kLongestFileName = 255 - (1 + 5 + 7 + 1 + 20);

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

} // namespace cutaway
