// tools/interrupt.cpp: the SIGINT and SIGTERM handler of `affray render` (rules in interrupt.h).
#include "tools/interrupt.h"

namespace affray::tools {
namespace {

std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "the signal handler may only touch lock-free atomics");

extern "C" void OnSignal(int signal) {
    // The first signal is the one reported.
    int none = 0;
    g_signal.compare_exchange_strong(none, signal);
    g_stop.store(true);
}

}  // namespace

Interrupts::Interrupts() {
    g_stop = false;
    g_signal = 0;
    struct sigaction action {};
    action.sa_handler = OnSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;
    sigaction(SIGINT, &action, &m_oldInt);
    sigaction(SIGTERM, &action, &m_oldTerm);
}

Interrupts::~Interrupts() {
    sigaction(SIGINT, &m_oldInt, nullptr);
    sigaction(SIGTERM, &m_oldTerm, nullptr);
}

const std::atomic<bool>& Interrupts::Flag() { return g_stop; }

int Interrupts::Signal() { return g_signal.load(); }

std::string Interrupts::SignalName(int signal) {
    return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "signal " + std::to_string(signal);
}

}  // namespace affray::tools
