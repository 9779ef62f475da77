// tools/interrupt.cpp: the SIGINT and SIGTERM handler of `affray render` (rules in interrupt.h).
#include "tools/interrupt.h"

namespace affray::tools {
namespace {

std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};
std::atomic<bool> g_timedOut{false};
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
    g_timedOut = false;
    struct sigaction action {};
    action.sa_handler = OnSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;
    sigaction(SIGINT, &action, &m_oldInt);
    sigaction(SIGTERM, &action, &m_oldTerm);
}

Interrupts::~Interrupts() {
    if (m_timer.joinable()) {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_finished = true;
        }
        m_done.notify_all();
        m_timer.join();
    }
    sigaction(SIGINT, &m_oldInt, nullptr);
    sigaction(SIGTERM, &m_oldTerm, nullptr);
}

void Interrupts::StopAfter(double seconds) {
    if (!(seconds > 0) || m_timer.joinable()) return;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    m_timer = std::thread([this, deadline] {
        std::unique_lock<std::mutex> lock(m_mutex);
        if (m_done.wait_until(lock, deadline, [this] { return m_finished; })) return;
        g_timedOut.store(true);
        g_stop.store(true);
    });
}

bool Interrupts::TimedOut() { return g_timedOut.load() && g_signal.load() == 0; }

const std::atomic<bool>& Interrupts::Flag() { return g_stop; }

int Interrupts::Signal() { return g_signal.load(); }

std::string Interrupts::SignalName(int signal) {
    return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "signal " + std::to_string(signal);
}

}  // namespace affray::tools
