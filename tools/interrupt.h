// tools/interrupt.h: SIGINT and SIGTERM during `affray render`. While an Interrupts object lives,
// either signal only sets a flag (the handler does nothing else, so it is async-signal-safe):
// the render's workers see it between samples and stop, and the command writes no image, keeps
// its checkpoint, and exits with 128 + the signal's number (130 for SIGINT, 143 for SIGTERM), as
// a shell reports a process the signal killed. The previous handlers come back when it dies.
#pragma once

#include <atomic>
#include <csignal>
#include <string>

namespace affray::tools {

class Interrupts {
  public:
    Interrupts();
    ~Interrupts();
    Interrupts(const Interrupts&) = delete;
    Interrupts& operator=(const Interrupts&) = delete;

    /// Set once a signal has come (RenderOptions::stop).
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
};

}  // namespace affray::tools
