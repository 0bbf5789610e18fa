#include "io/input_file.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <streambuf>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace cutaway {

namespace {

namespace fs = std::filesystem;

std::string cannotRead(std::string_view shownAs, std::string_view what, std::string_view reason) {
    std::string text(shownAs);
    text += ": cannot read ";
    text += what;
    text += " (";
    text += reason;
    text += ')';
    return text;
}

std::string notRegular(const struct stat& status) {
    return std::string("it is ") + nonRegularKind(status.st_mode) + ", not a regular file";
}

} // namespace

const char* nonRegularKind(mode_t mode) {
    if (S_ISREG(mode)) return nullptr;
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a named pipe (FIFO)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

std::optional<FileId> fileIdOf(const fs::path& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) == 0) return FileId{status.st_dev, status.st_ino, {}};
    std::error_code ec;
    fs::path target = path;
    // A dangling link: the file it would create. Only a few hops, as the kernel.
    for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(target, ec)); ++hops) {
        const fs::path next = fs::read_symlink(target, ec);
        if (ec) return std::nullopt;
        target = next.is_absolute() ? next : target.parent_path() / next;
    }
    if (fs::is_symlink(fs::symlink_status(target, ec))) return std::nullopt;
    const fs::path name = target.filename();
    if (name.empty() || name == "." || name == "..") return std::nullopt;
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    if (::stat(folder.c_str(), &status) != 0) return std::nullopt;
    return FileId{status.st_dev, status.st_ino, name.string()};
}

// A read-only, seekable stream buffer over a file descriptor.
class InputFile::Buffer : public std::streambuf {
public:
    explicit Buffer(int fd) : m_fd(fd), m_bytes(std::size_t{64} << 10) {}

protected:
    int_type underflow() override {
        if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
        const ssize_t got = readInto(m_bytes.data(), m_bytes.size());
        if (got <= 0) return traits_type::eof();
        setg(m_bytes.data(), m_bytes.data(), m_bytes.data() + got);
        return traits_type::to_int_type(*gptr());
    }

    std::streamsize xsgetn(char* dst, std::streamsize count) override {
        std::streamsize done = 0;
        while (done < count) {
            if (gptr() < egptr()) {
                const std::streamsize take =
                    std::min<std::streamsize>(egptr() - gptr(), count - done);
                std::memcpy(dst + done, gptr(), static_cast<std::size_t>(take));
                gbump(static_cast<int>(take));
                done += take;
                continue;
            }
            // Large reads go straight to the caller's memory.
            if (count - done >= static_cast<std::streamsize>(m_bytes.size())) {
                const ssize_t got = readInto(dst + done, static_cast<std::size_t>(count - done));
                if (got <= 0) break;
                done += got;
            } else if (underflow() == traits_type::eof()) {
                break;
            }
        }
        return done;
    }

    pos_type seekoff(off_type offset, std::ios_base::seekdir dir,
                     std::ios_base::openmode which) override {
        if ((which & std::ios_base::in) == 0) return pos_type(off_type(-1));
        off_type target = offset;
        if (dir == std::ios_base::cur) {
            const off_type at = ::lseek(m_fd, 0, SEEK_CUR);
            if (at < 0) return pos_type(off_type(-1));
            target += at - (egptr() - gptr());        // the buffered bytes are not read yet
            if (offset == 0) return pos_type(target); // tellg(): the buffer stays
        } else if (dir == std::ios_base::end) {
            struct stat status {};
            if (::fstat(m_fd, &status) != 0) return pos_type(off_type(-1));
            target += status.st_size;
        }
        if (target < 0 || ::lseek(m_fd, target, SEEK_SET) < 0) return pos_type(off_type(-1));
        setg(m_bytes.data(), m_bytes.data(), m_bytes.data());
        return pos_type(target);
    }

    pos_type seekpos(pos_type position, std::ios_base::openmode which) override {
        return seekoff(off_type(position), std::ios_base::beg, which);
    }

private:
    ssize_t readInto(char* dst, std::size_t size) {
        // A signal handler installed without SA_RESTART interrupts reads.
        constexpr std::size_t kMostAtOnce = std::size_t{1} << 30;
        for (;;) {
            const ssize_t got = ::read(m_fd, dst, std::min(size, kMostAtOnce));
            if (got >= 0 || errno != EINTR) return got;
        }
    }

    int m_fd;
    std::vector<char> m_bytes;
};

InputFile::InputFile(const fs::path& path, std::string_view what, std::string_view shownAs)
    : m_path(path), m_what(what), m_shownAs(shownAs.empty() ? path.string() : shownAs) {
    const std::string& shown = m_shownAs;
    struct stat status {};
    // Checked by name first: a device is never opened (opening some has effects).
    if (::stat(path.c_str(), &status) != 0) {
        const int err = errno;
        throw InputError(
            cannotRead(shown, what, err == ENOENT ? "no such file" : std::strerror(err)));
    }
    if (!S_ISREG(status.st_mode)) throw InputError(cannotRead(shown, what, notRegular(status)));
    // Without blocking: the path may have become a named pipe since.
    m_fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (m_fd < 0) {
        const int err = errno;
        throw InputError(cannotRead(shown, what, std::strerror(err)));
    }
    if (::fstat(m_fd, &status) != 0 || !S_ISREG(status.st_mode)) {
        const std::string reason = S_ISREG(status.st_mode) ? "fstat failed" : notRegular(status);
        ::close(m_fd);
        throw InputError(cannotRead(shown, what, reason));
    }
    // Reads of a regular file do not block anyway; clear the flag all the same.
    const int flags = ::fcntl(m_fd, F_GETFL);
    if (flags >= 0) (void)::fcntl(m_fd, F_SETFL, flags & ~O_NONBLOCK);
    m_size = static_cast<std::uint64_t>(status.st_size);
    m_id = FileId{status.st_dev, status.st_ino, {}};
}

InputFile::~InputFile() {
    m_stream.reset();
    m_buffer.reset();
    if (m_fd >= 0) ::close(m_fd);
}

std::istream& InputFile::stream() {
    if (!m_stream) {
        m_buffer = std::make_unique<Buffer>(m_fd);
        m_stream = std::make_unique<std::istream>(m_buffer.get());
    }
    return *m_stream;
}

std::string InputFile::readAll(std::uint64_t maxBytes) {
    const auto tooLarge = [&] {
        return InputError(cannotRead(m_shownAs, m_what,
                                     "it is larger than the " + std::to_string(maxBytes >> 20) +
                                         " MiB a " + m_what + " may be"));
    };
    if (m_size > maxBytes) throw tooLarge();
    std::istream& in = stream();
    in.seekg(0);
    std::string text(static_cast<std::size_t>(m_size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    // A file that grew since fstat: read on, up to the limit.
    char chunk[4096];
    while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
        text.append(chunk, static_cast<std::size_t>(in.gcount()));
        if (text.size() > maxBytes) throw tooLarge();
    }
    return text;
}

} // namespace cutaway
