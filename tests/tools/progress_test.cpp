// tests/tools/progress_test.cpp: the progress line (tools/progress.*): its text, the redraw
// throttle under a fake clock, silence when disabled, and counting from many threads.
#include "tools/progress.h"

#include <catch2/catch.hpp>
#include <thread>
#include <vector>

using namespace affray::tools;

namespace {

/// Everything written to `file` so far.
std::string Contents(std::FILE* file) {
    std::fflush(file);
    std::rewind(file);
    std::string text;
    char buffer[4096];
    for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, file)) > 0;) text.append(buffer, n);
    return text;
}

/// A tmpfile() closed at the end of the test.
struct TempFile {
    std::FILE* file = std::tmpfile();
    ~TempFile() {
        if (file) std::fclose(file);
    }
};

}  // namespace

TEST_CASE("The progress line shows the bar, the count, the time and the ETA", "[progress]") {
    // 30 of 120: a quarter of 20 cells; 10 s for 30 tiles leaves 30 s for the other 90.
    CHECK(Progress::Line(30, 120, 10) == "[#####...............] 30/120 tiles  elapsed 10.0s  ETA 30.0s");
    CHECK(Progress::Line(0, 10, 0) == "[....................] 0/10 tiles  elapsed 0.0s  ETA --");
    CHECK(Progress::Line(7, 7, 2.3) == "[####################] 7/7 tiles  elapsed 2.3s  ETA 0.0s");
    CHECK(Progress::Line(0, 0, 0) == "[####################] 0/0 tiles  elapsed 0.0s  ETA --");
}

TEST_CASE("A disabled progress reporter prints nothing", "[progress]") {
    TempFile out;
    REQUIRE(out.file);
    {
        Progress progress(3, out.file, false);
        for (int i = 0; i < 3; ++i) progress.TileDone();
        progress.Finish();
        CHECK(progress.done() == 3);
    }
    CHECK(Contents(out.file).empty());
}

TEST_CASE("Redraws are throttled and the last tile and Finish always draw", "[progress]") {
    TempFile out;
    REQUIRE(out.file);
    double now = 0;
    Progress progress(4, out.file, true, [&] { return now; });
    now = 1.0;
    progress.TileDone();  // the first tile draws
    now = 1.05;
    progress.TileDone();  // within 0.1 s of the last draw: silent
    now = 1.2;
    progress.TileDone();  // draws
    now = 1.21;
    progress.TileDone();  // the last tile draws at once
    now = 1.3;
    progress.Finish();
    progress.Finish();  // only once
    const std::string want = "\r" + Progress::Line(1, 4, 1.0) + "\r" + Progress::Line(3, 4, 1.2) + "\r" +
                             Progress::Line(4, 4, 1.21) + "\r" + Progress::Line(4, 4, 1.3) + "\n";
    CHECK(Contents(out.file) == want);
}

TEST_CASE("A shorter progress line blanks the rest of the longer one", "[progress]") {
    TempFile out;
    REQUIRE(out.file);
    double now = 0;
    Progress progress(3, out.file, true, [&] { return now; });
    now = 50;
    progress.TileDone();  // ETA 100.0s
    now = 60;
    progress.TileDone();  // ETA 30.0s: one character shorter
    const std::string first = Progress::Line(1, 3, 50), second = Progress::Line(2, 3, 60);
    REQUIRE(second.size() + 1 == first.size());
    CHECK(Contents(out.file) == "\r" + first + "\r" + second + " ");
    progress.Finish();
}

TEST_CASE("Progress counts tiles from many threads", "[progress]") {
    TempFile out;
    REQUIRE(out.file);
    constexpr int kThreads = 4, kTilesEach = 500, kTotal = kThreads * kTilesEach;
    {
        // Interval 0: every tile redraws, the most contention there can be.
        Progress progress(
            kTotal, out.file, true, [] { return 0.0; }, 0.0);
        std::vector<std::thread> threads;
        threads.reserve(kThreads);
        for (int t = 0; t < kThreads; ++t)
            threads.emplace_back([&] {
                for (int i = 0; i < kTilesEach; ++i) progress.TileDone();
            });
        for (std::thread& t : threads) t.join();
        CHECK(progress.done() == kTotal);
        progress.Finish();
    }
    const std::string text = Contents(out.file);
    CHECK(std::count(text.begin(), text.end(), '\r') == kTotal + 1);
    const std::string last = "\r" + Progress::Line(kTotal, kTotal, 0) + "\n";
    REQUIRE(text.size() >= last.size());
    CHECK(text.substr(text.size() - last.size()) == last);
}

TEST_CASE("Progress shows only on a terminal and when not quiet", "[progress]") {
    TempFile out;
    REQUIRE(out.file);
    CHECK_FALSE(Progress::ShouldShow(false, out.file));  // a file is not a terminal
    CHECK_FALSE(Progress::ShouldShow(true, out.file));
    CHECK_FALSE(Progress::ShouldShow(false, nullptr));
    CHECK_FALSE(Progress::ShouldShow(true, stderr));
}
