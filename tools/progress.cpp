// tools/progress.cpp: the throttled progress line (see progress.h).
#include "tools/progress.h"

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>

namespace affray::tools {

namespace {

constexpr int kBarWidth = 20;

double SteadySeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

Progress::Progress(int totalTiles, std::FILE* out, bool enabled, Clock clock, double minInterval)
    : m_total(std::max(totalTiles, 0)),
      m_out(out),
      m_enabled(enabled && out != nullptr),
      m_clock(clock ? std::move(clock) : Clock(SteadySeconds)),
      m_minInterval(minInterval),
      m_start(m_clock()) {}

Progress::~Progress() { Finish(); }

bool Progress::ShouldShow(bool quiet, std::FILE* out) { return !quiet && out != nullptr && isatty(fileno(out)); }

std::string Progress::Line(int done, int total, double elapsedSeconds) {
    const int filled =
        total > 0 ? static_cast<int>(static_cast<long long>(std::min(done, total)) * kBarWidth / total) : kBarWidth;
    std::string line = "[" + std::string(filled, '#') + std::string(kBarWidth - filled, '.') + "] ";
    char text[128];
    std::snprintf(text, sizeof text, "%d/%d tiles  elapsed %.1fs  ETA ", done, total, elapsedSeconds);
    line += text;
    if (done > 0) {
        // Assumes the remaining tiles cost what the finished ones did on average.
        std::snprintf(text, sizeof text, "%.1fs", elapsedSeconds * (total - done) / done);
        line += text;
    } else {
        line += "--";
    }
    return line;
}

void Progress::TileDone() {
    const int done = ++m_done;
    if (!m_enabled) return;
    const double now = m_clock();
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_finished) return;
    // The last tile always draws, so the bar ends full even inside the redraw interval.
    if (done == m_total || now - m_lastDraw >= m_minInterval) Draw(m_done.load(), now);
}

void Progress::Finish() {
    if (!m_enabled) return;
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_finished) return;
    Draw(m_done.load(), m_clock());
    std::fputc('\n', m_out);
    std::fflush(m_out);
    m_finished = true;
}

void Progress::Draw(int done, double now) {
    std::string line = Line(done, m_total, now - m_start);
    // Blank out what a longer previous line left behind (an ETA that lost a digit).
    const size_t length = line.size();
    if (length < m_lastLength) line += std::string(m_lastLength - length, ' ');
    m_lastLength = length;
    std::fprintf(m_out, "\r%s", line.c_str());
    std::fflush(m_out);
    m_lastDraw = now;
}

}  // namespace affray::tools
