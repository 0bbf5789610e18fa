#include "interrupt.hpp"

#include "io/atomic_file.hpp"

#include <atomic>
#include <csignal>
#include <ctime>

namespace cutaway::cli {
namespace {

constexpr int kEndingSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

std::atomic<int> g_signal{0};
std::atomic<long long> g_firstNs{0};
std::atomic<bool> g_endAtOnce{false};

long long monotonicNs() {
    timespec now{};
    ::clock_gettime(CLOCK_MONOTONIC, &now); // async-signal-safe
    return static_cast<long long>(now.tv_sec) * 1000000000LL + now.tv_nsec;
}

void endNow(int sig) {
    removeTemporariesNow();
    std::signal(sig, SIG_DFL);
    std::raise(sig); // delivered when the handler returns
}

extern "C" void onSignal(int sig) {
    constexpr long long kSameRequestNs = 250000000LL;
    if (g_endAtOnce.load()) {
        endNow(sig);
        return;
    }
    const long long now = monotonicNs();
    int none = 0;
    if (g_signal.compare_exchange_strong(none, sig)) {
        g_firstNs.store(now);
        return;
    }
    if (now - g_firstNs.load() < kSameRequestNs) return;
    endNow(sig);
}

void install() {
    struct sigaction action {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    for (const int sig : kEndingSignals) // one handler at a time
        sigaddset(&action.sa_mask, sig);
    for (const int sig : kEndingSignals)
        ::sigaction(sig, &action, nullptr);
}

} // namespace

void ignoreBrokenPipes() {
    struct sigaction action {};
    action.sa_handler = SIG_IGN;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGPIPE, &action, nullptr);
}

void installInterruptHandlers() {
    g_endAtOnce.store(false);
    install();
}

void installEndingHandlers() {
    g_endAtOnce.store(true);
    install();
}

int interruptSignal() {
    return g_signal.load();
}

} // namespace cutaway::cli
