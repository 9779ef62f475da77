// tools/progress.h: a one-line progress bar for tiled renders, safe to feed from many threads.
//
// A render calls TileDone() from its worker threads and Finish() once at the end; the bar is
// redrawn in place ("\r...") at most once per redraw interval (0.1 s), plus once when the last
// tile is done, so printing costs nothing measurable. A disabled reporter prints nothing at all:
// decide with ShouldShow(quiet, stderr), so logs and pipes never see carriage returns.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>

namespace affray::tools {

class Progress {
  public:
    /// Seconds on any monotonic scale; tests inject a fake one.
    using Clock = std::function<double()>;

    /// Reports on `out` if `enabled`; `clock` defaults to std::chrono::steady_clock. Redraws are
    /// at least `minInterval` seconds apart (0: redraw on every tile).
    Progress(int totalTiles, std::FILE* out, bool enabled, Clock clock = {}, double minInterval = 0.1);
    /// Finishes the line if Finish() was not called, so an early return leaves no dangling bar.
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    /// Counts one finished tile; callable from any thread.
    void TileDone();
    /// Draws the final state and ends the line. Only the first call prints.
    void Finish();
    int done() const { return m_done.load(); }

    /// Whether to show progress: not `quiet`, and `out` is a terminal.
    static bool ShouldShow(bool quiet, std::FILE* out);

    /// The text of one redraw, without the leading '\r':
    /// "[########............] 37/120 tiles  elapsed 12.3s  ETA 21.0s" (ETA "--" before the first tile).
    static std::string Line(int done, int total, double elapsedSeconds);

  private:
    void Draw(int done, double now);  // caller holds m_mutex

    const int m_total;
    std::FILE* const m_out;
    const bool m_enabled;
    const Clock m_clock;
    const double m_minInterval;
    const double m_start;
    std::atomic<int> m_done{0};
    std::mutex m_mutex;  // serialises drawing, so lines never interleave
    double m_lastDraw = -INFINITY;
    size_t m_lastLength = 0;
    bool m_finished = false;
};

}  // namespace affray::tools
