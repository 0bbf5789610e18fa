#pragma once
// A named pipe that nobody writes to, for tests of readers that must refuse
// it: opening it for reading would block for ever. While it exists, a thread
// opens its write end whenever a reader waits on it (and closes it at once),
// so a reader that wrongly opens it gets end of file instead of hanging the
// test, and wasOpened() tells that it happened.
#include <atomic>
#include <chrono>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

namespace cutaway::test {

class NamedPipe {
public:
    explicit NamedPipe(std::filesystem::path path) : m_path(std::move(path)) {
        m_made = ::mkfifo(m_path.c_str(), 0600) == 0;
        m_thread = std::thread([this] {
            while (!m_stop.load()) {
                // Succeeds only while a reader has it open or waits in open().
                const int fd = ::open(m_path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
                if (fd >= 0) {
                    m_opened.store(true);
                    ::close(fd);
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
            }
        });
    }
    ~NamedPipe() {
        m_stop.store(true);
        m_thread.join();
        std::error_code ignored;
        std::filesystem::remove(m_path, ignored);
    }
    NamedPipe(const NamedPipe&) = delete;
    NamedPipe& operator=(const NamedPipe&) = delete;

    bool made() const { return m_made; }
    /// Whether a reader opened the pipe (a reader that refuses it never does).
    bool wasOpened() const { return m_opened.load(); }
    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path m_path;
    bool m_made = false;
    std::atomic<bool> m_stop{false};
    std::atomic<bool> m_opened{false};
    std::thread m_thread;
};

} // namespace cutaway::test
