#pragma once
// Running a third-party parser where it cannot take cutaway down: in a child
// process (fork, no exec), which sends its result back through a pipe. An
// assertion, a crash or a runaway allocation inside the library ends the
// child only; the parent turns that into an error naming the file the child
// was reading. The DICOM reader (GDCM) goes through here.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cutaway::detail {

/// The child's end of the pipe.
class ChildChannel {
public:
    explicit ChildChannel(int fd) : m_fd(fd) {}
    /// Says what the child is about to read (a file's name): named by the
    /// parent's error if the child dies before the next progress or result.
    void progress(std::string_view what);
    /// The child's result, once.
    void result(std::span<const std::byte> bytes);

private:
    friend void runChildWork(int fd, const std::function<void(ChildChannel&)>& work);
    void record(char kind, std::span<const std::byte> bytes);
    int m_fd;
};

/// Runs `work` in a child process and returns the bytes it gave
/// ChildChannel::result. An InputError the child throws is thrown again here
/// with its message; any other exception as a RuntimeError. A child killed
/// by a signal (an assertion's abort, a crash) or ending without a result
/// throws InputError from `died(last progress, signal number or 0, the last
/// line the child wrote to stderr)`, when the signal is one a damaged input
/// causes (SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL), else RuntimeError. The
/// child's stderr (the messages of `library`, its name) is kept from the
/// terminal unless showChildMessages is on; the child writes no core file
/// and runs no exit handlers.
using ChildDied = std::function<std::string(const std::string&, int, const std::string&)>;
std::vector<std::byte> runInChild(const std::function<void(ChildChannel&)>& work,
                                  const ChildDied& died, const char* library);

/// Whether runInChild prints what its children wrote to stderr, each line
/// escaped, after "cutaway: LIBRARY: " (`--verbose`). Off by default.
void showChildMessages(bool on);

/// Bytes written field by field, and read back in the same order: the
/// child's results. Reading past the end throws RuntimeError.
class Wire {
public:
    void u64(std::uint64_t v);
    void f64(double v);
    void str(std::string_view s);
    void bytes(std::span<const std::byte> b); ///< its length, then the bytes
    const std::vector<std::byte>& data() const { return m_data; }

private:
    void append(std::span<const std::byte> b);
    std::vector<std::byte> m_data;
};

class WireReader {
public:
    explicit WireReader(std::span<const std::byte> data) : m_data(data) {}
    std::uint64_t u64();
    double f64();
    std::string str();
    std::vector<std::byte> bytes();

private:
    std::span<const std::byte> take(std::size_t n);
    std::span<const std::byte> m_data;
    std::size_t m_at = 0;
};

} // namespace cutaway::detail
