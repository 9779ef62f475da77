// tools/interrupt.h: SIGINT and SIGTERM during `affray render`. While an Interrupts object lives,
// either signal only sets a flag (the handler does nothing else, so it is async-signal-safe):
// the render's workers see it between samples and stop, and the command writes no image, keeps
// its checkpoint, and exits with 128 + the signal's number (130 for SIGINT, 143 for SIGTERM), as
// a shell reports a process the signal killed. The previous handlers come back when it dies.
// A wall-clock time limit (`--time-limit S`, the time-limit limit of diag/limits.h) stops the
// render the same way when it runs out: no image, the checkpoint kept, exit status 4
// (kExitResources) with an error naming the limit.
#pragma once

#include <atomic>
#include <condition_variable>
#include <csignal>
#include <mutex>
#include <string>
#include <thread>

namespace affray::tools {

class Interrupts {
  public:
    Interrupts();
    ~Interrupts();
    Interrupts(const Interrupts&) = delete;
    Interrupts& operator=(const Interrupts&) = delete;

    /// Sets the flag `seconds` of wall-clock time from now (0: never), unless this object dies
    /// first. Call once.
    void StopAfter(double seconds);
    /// True if the time limit, not a signal, set the flag.
    static bool TimedOut();

    /// Set once a signal has come or the time limit has run out (RenderControl::stop).
    static const std::atomic<bool>& Flag();
    /// The signal that came (SIGINT or SIGTERM), 0 if none.
    static int Signal();
    /// "SIGINT" or "SIGTERM".
    static std::string SignalName(int signal);
    /// 128 + signal: the conventional exit status of a process a signal stopped.
    static int ExitCode(int signal) { return 128 + signal; }

  private:
    struct sigaction m_oldInt {
    }, m_oldTerm{};
    std::mutex m_mutex;
    std::condition_variable m_done;
    bool m_finished = false;
    std::thread m_timer;
};

}  // namespace affray::tools
