#include "interrupt.hpp"

#include <atomic>
#include <csignal>

namespace cutaway::cli {
namespace {

std::atomic<int> g_signal{0};

extern "C" void onSignal(int sig) {
    g_signal.store(sig);
    std::signal(sig, SIG_DFL); // a second signal ends the process
}

} // namespace

void installInterruptHandlers() {
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
}

int interruptSignal() {
    return g_signal.load();
}

} // namespace cutaway::cli
