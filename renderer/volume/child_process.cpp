#include "volume/child_process.hpp"

#include "core/error.hpp"
#include "core/quote_text.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace cutaway::detail {
namespace {

// Records on the pipe: a kind byte, a 64-bit length, the bytes.
constexpr char kProgress = 'P', kResult = 'R', kInputError = 'E', kOtherError = 'X';

bool writeAll(int fd, const void* data, std::size_t size) {
    const auto* p = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::write(fd, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n, size -= std::size_t(n);
    }
    return true;
}

// Reads exactly `size` bytes; false at the end of the pipe.
bool readAll(int fd, void* data, std::size_t size) {
    auto* p = static_cast<char*>(data);
    while (size > 0) {
        const ssize_t n = ::read(fd, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n, size -= std::size_t(n);
    }
    return true;
}

std::span<const std::byte> bytesOf(std::string_view s) {
    return std::as_bytes(std::span<const char>(s.data(), s.size()));
}

bool damagedInput(int signal) {
    return signal == SIGABRT || signal == SIGSEGV || signal == SIGBUS || signal == SIGFPE ||
           signal == SIGILL;
}

// The exit status of `child`, waited for.
int waitFor(pid_t child) {
    int status = 0;
    while (::waitpid(child, &status, 0) < 0)
        if (errno != EINTR) throw RuntimeError(std::string("waitpid: ") + std::strerror(errno));
    return status;
}

std::atomic<bool> g_showMessages{false};

// What the child wrote to `fd` (its stderr, a memory file): its first MiB.
std::string messagesIn(int fd) {
    std::string text;
    char buffer[4096];
    ::lseek(fd, 0, SEEK_SET);
    for (ssize_t n; text.size() < (1u << 20) && (n = ::read(fd, buffer, sizeof buffer)) > 0;)
        text.append(buffer, std::size_t(n));
    return text;
}

// The last non-empty line of `text`, escaped, at most 200 characters.
std::string lastLine(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
        text.pop_back();
    text =
        text.substr(text.find_last_of('\n') == std::string::npos ? 0 : text.find_last_of('\n') + 1);
    return escapeText(text, 200);
}

// Each non-empty line of `text` on stderr, escaped, after `library`'s name.
void show(const std::string& text, const char* library) {
    std::size_t start = 0;
    while (start < text.size()) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        if (end > start)
            std::fprintf(
                stderr, "cutaway: %s: %s\n", library,
                escapeText(std::string_view(text).substr(start, end - start), 500).c_str());
        start = end + 1;
    }
}

} // namespace

void ChildChannel::record(char kind, std::span<const std::byte> bytes) {
    const std::uint64_t size = bytes.size();
    if (!writeAll(m_fd, &kind, 1) || !writeAll(m_fd, &size, sizeof size) ||
        !writeAll(m_fd, bytes.data(), bytes.size()))
        ::_exit(3); // the parent is gone
}

void ChildChannel::progress(std::string_view what) {
    record(kProgress, bytesOf(what));
}

void ChildChannel::result(std::span<const std::byte> bytes) {
    record(kResult, bytes);
}

void runChildWork(int fd, const std::function<void(ChildChannel&)>& work) {
    const rlimit noCore{0, 0};
    ::setrlimit(RLIMIT_CORE, &noCore);
    ChildChannel channel(fd);
    try {
        work(channel);
    } catch (const InputError& e) {
        channel.record(kInputError, bytesOf(e.what()));
    } catch (const std::exception& e) {
        channel.record(kOtherError, bytesOf(e.what()));
    } catch (...) {
        channel.record(kOtherError, bytesOf("an unknown exception"));
    }
    ::_exit(0);
}

void showChildMessages(bool on) {
    g_showMessages = on;
}

std::vector<std::byte> runInChild(const std::function<void(ChildChannel&)>& work,
                                  const ChildDied& died, const char* library) {
    int fds[2];
    if (::pipe(fds) != 0) throw RuntimeError(std::string("pipe: ") + std::strerror(errno));
    const int messages = ::memfd_create("cutaway-child-stderr", MFD_CLOEXEC);
    const pid_t child = messages < 0 ? -1 : ::fork();
    if (child < 0) {
        const int error = errno;
        ::close(fds[0]), ::close(fds[1]);
        if (messages >= 0) ::close(messages);
        throw RuntimeError(std::string("fork: ") + std::strerror(error));
    }
    if (child == 0) {
        ::close(fds[0]);
        ::dup2(messages, STDERR_FILENO);
        runChildWork(fds[1], work);
    }
    ::close(fds[1]);
    std::string last;
    std::vector<std::byte> result;
    char outcome = 0;
    std::string message;
    for (char kind = 0; readAll(fds[0], &kind, 1);) {
        std::uint64_t size = 0;
        if (!readAll(fds[0], &size, sizeof size)) break;
        std::vector<std::byte> bytes(size);
        if (!readAll(fds[0], bytes.data(), size)) break;
        if (kind == kProgress) {
            last.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        } else {
            outcome = kind;
            if (kind == kResult)
                result = std::move(bytes);
            else
                message.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        }
    }
    ::close(fds[0]);
    const int status = waitFor(child);
    const std::string text = messagesIn(messages);
    ::close(messages);
    if (g_showMessages) show(text, library);
    const std::string said = lastLine(text);
    if (outcome == kResult && WIFEXITED(status) && WEXITSTATUS(status) == 0) return result;
    if (outcome == kInputError) throw InputError(message);
    if (outcome == kOtherError) throw RuntimeError(message);
    const int signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    if (signal == 0 || damagedInput(signal)) throw InputError(died(last, signal, said));
    throw RuntimeError(died(last, signal, said));
}

void Wire::append(std::span<const std::byte> b) {
    m_data.insert(m_data.end(), b.begin(), b.end());
}

void Wire::u64(std::uint64_t v) {
    append(std::as_bytes(std::span<const std::uint64_t>(&v, 1)));
}

void Wire::f64(double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof v);
    u64(bits);
}

void Wire::str(std::string_view s) {
    bytes(bytesOf(s));
}

void Wire::bytes(std::span<const std::byte> b) {
    u64(b.size());
    append(b);
}

std::span<const std::byte> WireReader::take(std::size_t n) {
    if (n > m_data.size() - m_at) throw RuntimeError("a child process's result ended early");
    const auto part = m_data.subspan(m_at, n);
    m_at += n;
    return part;
}

std::uint64_t WireReader::u64() {
    std::uint64_t v = 0;
    std::memcpy(&v, take(sizeof v).data(), sizeof v);
    return v;
}

double WireReader::f64() {
    const std::uint64_t bits = u64();
    double v = 0;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

std::string WireReader::str() {
    const auto part = take(u64());
    return std::string(reinterpret_cast<const char*>(part.data()), part.size());
}

std::vector<std::byte> WireReader::bytes() {
    const auto part = take(u64());
    return {part.begin(), part.end()};
}

} // namespace cutaway::detail
