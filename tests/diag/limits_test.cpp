// tests/diag/limits_test.cpp: the limits table (diag/limits.h): parsing --limit, clamping,
// the note every limit's error ends with, and bounded reading of source files.
#include <catch2/catch.hpp>

#include <string>

#include "diag/limits.h"
#include "tests/test_util.h"

using namespace affray;
using diag::Limit;

TEST_CASE("limits: every limit has a distinct name and a default within its range", "[diag][limits]") {
    for (int i = 0; i < diag::kLimitCount; ++i) {
        const diag::LimitInfo& info = diag::Info(static_cast<Limit>(i));
        INFO(info.name);
        CHECK(static_cast<int>(info.limit) == i);
        CHECK(diag::FindLimit(info.name) == &info);
        CHECK(info.minValue <= info.defaultValue);
        CHECK(info.defaultValue <= info.maxValue);
        CHECK(diag::LimitValue(info.limit) == info.defaultValue);
        CHECK(diag::LimitsTable().find(std::string(info.name) + " ") != std::string::npos);
    }
    CHECK(diag::FindLimit("no-such-limit") == nullptr);
}

TEST_CASE("limits: --limit NAME=VALUE sets a limit, and bad ones are refused with the reason", "[diag][limits]") {
    CHECK_FALSE(diag::ApplyLimit("loop-iterations=250k"));
    CHECK(diag::LimitValue(Limit::LoopIterations) == 250000);
    CHECK_FALSE(diag::ApplyLimit("program-ops=2M"));
    CHECK(diag::LimitValue(Limit::ProgramOps) == 2000000);
    CHECK_FALSE(diag::ApplyLimit("time-limit=0"));
    CHECK(diag::LimitNote(Limit::LoopIterations) ==
          "(limit loop-iterations = 250000; raise it with --limit loop-iterations=N)");

    CHECK(diag::ApplyLimit("loop-iteration=5")
              .value_or("")
              .find("unknown limit 'loop-iteration' (limits: "
                    "source-bytes, include-depth,") == 0);
    CHECK(diag::ApplyLimit("nesting") == "--limit takes NAME=VALUE, as --limit nesting=N");
    CHECK(diag::ApplyLimit("nesting=") == "limit nesting takes a whole number from 16 to 2000, not ''");
    CHECK(diag::ApplyLimit("nesting=-1") == "limit nesting takes a whole number from 16 to 2000, not '-1'");
    CHECK(diag::ApplyLimit("nesting=1.5") == "limit nesting takes a whole number from 16 to 2000, not '1.5'");
    CHECK(diag::ApplyLimit("nesting=3000") == "limit nesting takes a whole number from 16 to 2000, not '3000'");
    CHECK(diag::ApplyLimit("nesting=8") == "limit nesting takes a whole number from 16 to 2000, not '8'");
    CHECK(diag::ApplyLimit("call-depth=99999999999999999999").has_value());
    CHECK(diag::ApplyLimit("image-pixels=3G").has_value());  // past the maximum, 2^31
    CHECK(diag::LimitValue(Limit::Nesting) == 1000);         // unchanged by the refusals

    diag::SetLimit(Limit::CallDepth, 100000);  // clamped to the maximum
    CHECK(diag::LimitValue(Limit::CallDepth) == 256);
    diag::ResetLimits();
    CHECK(diag::LimitValue(Limit::LoopIterations) == 10000);
    CHECK(diag::LimitValue(Limit::CallDepth) == 64);
}

TEST_CASE("limits: a source file past source-bytes is refused, not read", "[diag][limits]") {
    test::TempDir dir;
    const std::string big = dir.Write("big.sl", std::string(3000, 'x'));
    const std::string small = dir.Write("small.sl", std::string(2000, 'y'));
    test::ScopedLimit limit(Limit::SourceBytes, 2048);
    std::string bytes = "old";
    CHECK(diag::ReadSourceFile(small, &bytes).empty());
    CHECK(bytes == std::string(2000, 'y'));
    CHECK(diag::ReadSourceFile(big, &bytes) ==
          "file larger than 2048 bytes (limit source-bytes = 2048; raise it with --limit source-bytes=N)");
    CHECK(bytes.empty());
    CHECK(diag::ReadSourceFile(dir.Path("missing.sl"), &bytes) == "cannot open file: No such file or directory");
    // A pipe has no size: it is read up to one byte past the limit, then refused.
    if (std::filesystem::exists("/dev/zero")) {
        CHECK(diag::ReadSourceFile("/dev/zero", &bytes).find("file larger than 2048 bytes") == 0);
        CHECK(bytes.empty());
    }
}
