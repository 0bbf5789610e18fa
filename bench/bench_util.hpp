#pragma once
// Small helpers the benchmarks share: wall-clock timing, order statistics and
// the process's peak resident memory. Benchmarks report; nothing here asserts.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace cutaway::bench {

inline double millisecondsOf(const std::function<void()>& body) {
    const auto start = std::chrono::steady_clock::now();
    body();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

/// Seconds on the steady clock (CLOCK_MONOTONIC on Linux, the same in every
/// process).
inline double steadySeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

struct Stats {
    double median = 0.0, min = 0.0, max = 0.0;
};

inline Stats statsOf(std::vector<double> ms) {
    if (ms.empty()) return {};
    std::sort(ms.begin(), ms.end());
    const std::size_t n = ms.size();
    const double median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
    return {median, ms.front(), ms.back()};
}

/// The median of `repeats` runs of `body`, in milliseconds.
inline double medianMs(int repeats, const std::function<void()>& body) {
    std::vector<double> ms;
    for (int i = 0; i < repeats; ++i)
        ms.push_back(millisecondsOf(body));
    return statsOf(ms).median;
}

/// A line of /proc/self/status in MiB ("VmHWM", "VmRSS"); 0 where unavailable.
inline double procStatusMiB(const std::string& key) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind(key + ":", 0) == 0) return std::stod(line.substr(key.size() + 1)) / 1024.0;
    }
    return 0.0;
}

/// Peak resident memory of this process so far (since the last reset), MiB.
inline double peakRssMiB() {
    return procStatusMiB("VmHWM");
}

/// Starts peak resident memory afresh from the current resident size (Linux:
/// writing 5 to /proc/self/clear_refs). Returns false where unsupported.
inline bool resetPeakRss() {
    std::ofstream clear("/proc/self/clear_refs");
    return static_cast<bool>(clear << "5" << std::flush);
}

} // namespace cutaway::bench
