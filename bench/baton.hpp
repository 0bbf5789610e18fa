#pragma once
// Turn-taking between two benchmark processes (bench/ab_interleave.py): each
// renders only while it holds the turn, and passes it on between frames once
// it has held it for a slice of time, so two builds compared frame by frame
// meet the same drift of the machine's speed within seconds. The turn is the
// content of a file ("0" or "1"); a process that is done leaves a marker
// (the file's name + ".done" + its id) so the other stops waiting. Each
// dataset runs in a child process of its own (table1_bench.cpp), with a
// Baton of its own that hands the turn over at its end.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace cutaway::bench {

class Baton {
public:
    Baton(std::filesystem::path file, int id, double sliceSeconds)
        : m_file(std::move(file)), m_id(id), m_slice(sliceSeconds) {}

    /// Waits for this process's turn (at once without a file, or once the other is done).
    void acquire() {
        if (m_file.empty() || m_held) return;
        while (read() != m_id && !std::filesystem::exists(marker(1 - m_id)))
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        m_held = true;
        m_since = std::chrono::steady_clock::now();
    }

    /// After a frame: passes the turn on once this process has held it for a slice.
    void release() {
        if (m_file.empty() || !m_held) return;
        const std::chrono::duration<double> held = std::chrono::steady_clock::now() - m_since;
        if (held.count() >= m_slice) pass();
    }

    /// Passes the turn on if this process holds it (a dataset's child process
    /// at its end: the next dataset's takes its turn afresh).
    void handOver() {
        if (!m_file.empty() && m_held) pass();
    }

    /// Passes the turn on for good (the benchmark's main process, after its
    /// datasets).
    void finish() {
        if (m_file.empty()) return;
        std::ofstream(marker(m_id)) << "done\n";
        pass();
    }

private:
    std::filesystem::path marker(int id) const {
        return m_file.string() + ".done" + std::to_string(id);
    }
    int read() const {
        std::ifstream in(m_file);
        int id = -1;
        in >> id;
        return id;
    }
    void pass() {
        const std::filesystem::path tmp = m_file.string() + ".tmp" + std::to_string(m_id);
        std::ofstream(tmp) << 1 - m_id << "\n";
        std::filesystem::rename(tmp, m_file); // atomic: the other never reads half a file
        m_held = false;
    }

    std::filesystem::path m_file;
    int m_id = 0;
    double m_slice = 2.0;
    bool m_held = false;
    std::chrono::steady_clock::time_point m_since;
};

} // namespace cutaway::bench
