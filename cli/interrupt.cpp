#include "interrupt.hpp"

#include "io/atomic_file.hpp"

#include <atomic>
#include <csignal>
#include <ctime>

namespace cutaway::cli {
namespace {

std::atomic<int> g_signal{0};
std::atomic<long long> g_firstNs{0};

long long monotonicNs() {
    timespec now{};
    ::clock_gettime(CLOCK_MONOTONIC, &now); // async-signal-safe
    return static_cast<long long>(now.tv_sec) * 1000000000LL + now.tv_nsec;
}

extern "C" void onSignal(int sig) {
    constexpr long long kSameRequestNs = 250000000LL;
    const long long now = monotonicNs();
    int none = 0;
    if (g_signal.compare_exchange_strong(none, sig)) {
        g_firstNs.store(now);
        return;
    }
    if (now - g_firstNs.load() < kSameRequestNs) return;
    removeTemporariesNow();
    std::signal(sig, SIG_DFL);
    std::raise(sig); // delivered when this handler returns
}

} // namespace

void installInterruptHandlers() {
    struct sigaction action {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    sigaddset(&action.sa_mask, SIGINT); // one handler at a time
    sigaddset(&action.sa_mask, SIGTERM);
    ::sigaction(SIGINT, &action, nullptr);
    ::sigaction(SIGTERM, &action, nullptr);
}

int interruptSignal() {
    return g_signal.load();
}

} // namespace cutaway::cli
