#pragma once
// Opening the files a run reads (the scene, volumes and their detached data,
// label volumes, glTF models and the buffers they name), all alike: only a
// regular file is read. The path is checked first and the file is then
// opened without blocking (a named pipe without a writer would block open()
// for ever) and checked again on its descriptor, so a folder, a pipe or a
// device such as /dev/zero is refused with a message that says what it is,
// never read until memory runs out.
//
//   InputFile file(path, "volume");   // "PATH: cannot read volume (it is a folder)"
//   std::istream& in = file.stream(); // buffered, seekable
#include <cstdint>
#include <filesystem>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <sys/types.h>

namespace cutaway {

/// What a file that is not a regular one is, for messages: "a folder", "a
/// named pipe (FIFO)", "a character device", "a block device", "a socket";
/// null for a regular file.
const char* nonRegularKind(mode_t mode);

/// Which file a path names, compared as files rather than as text: the
/// device and inode of an existing file (links followed), or for a path that
/// does not exist yet the device and inode of its folder and its name.
struct FileId {
    dev_t device = 0;
    ino_t inode = 0;
    std::string name; ///< empty for an existing file
    bool operator==(const FileId&) const = default;
};

/// The FileId of `path`; nullopt when neither it nor its folder exists (or a
/// link on the way loops). A dangling link names the file it would create.
std::optional<FileId> fileIdOf(const std::filesystem::path& path);

class InputFile {
public:
    /// Opens `path` for reading. `what` names it in messages ("scene",
    /// "volume", "glTF buffer"). Throws InputError "PATH: cannot read WHAT
    /// (REASON)" when it does not exist, is not a regular file (REASON says
    /// what it is) or cannot be opened; `shownAs`, if given, stands for PATH.
    InputFile(const std::filesystem::path& path, std::string_view what,
              std::string_view shownAs = {});
    ~InputFile();
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    const std::filesystem::path& path() const { return m_path; }
    std::uint64_t size() const { return m_size; }
    FileId id() const { return m_id; }
    /// The file's bytes as a stream, buffered and seekable.
    std::istream& stream();
    /// The whole file; throws InputError "PATH: cannot read WHAT (it is larger
    /// than the N MiB a WHAT may be)" past `maxBytes`.
    std::string readAll(std::uint64_t maxBytes);

private:
    class Buffer;
    std::filesystem::path m_path;
    std::string m_what;
    std::string m_shownAs;
    int m_fd = -1;
    std::uint64_t m_size = 0;
    FileId m_id;
    std::unique_ptr<Buffer> m_buffer;
    std::unique_ptr<std::istream> m_stream;
};

} // namespace cutaway
