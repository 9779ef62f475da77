// diag/limits.cpp: the limits table and its process-wide values.
#include "diag/limits.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <system_error>

namespace affray::diag {

namespace {

// In the order of enum Limit. The defaults are far above what real shaders and scenes need and
// low enough that reaching one costs well under a second and a few hundred MB; the maxima keep
// what the code behind each limit was written for (int lengths, the stack depth of recursive
// passes, mcpp's own 256-deep #include stack).
constexpr std::array<LimitInfo, kLimitCount> kTable{{
    {Limit::SourceBytes, "source-bytes", int64_t{16} << 20, 1024, int64_t{256} << 20, "bytes",
     "size of one shader or compiled shader file, and of a shader after preprocessing"},
    {Limit::IncludeDepth, "include-depth", 64, 1, 200, "files", "#include files nested in each other"},
    {Limit::Nesting, "nesting", 1000, 16, 2000, "levels",
     "nesting of expressions, statements and brackets in a shader"},
    {Limit::ProgramOps, "program-ops", 250'000, 1000, 16'000'000, "operations",
     "operations a shader asks for as it is lowered, with its loops unrolled and calls inlined"},
    {Limit::LoopIterations, "loop-iterations", 10'000, 1, 10'000'000, "iterations",
     "iterations of a loop whose count is known when it is compiled (loops are unrolled)"},
    {Limit::VaryingLoopIterations, "varying-loop-iterations", 64, 1, 4096, "iterations",
     "iterations unrolled of a loop whose count varies over the surface (paths past it are unbounded)"},
    {Limit::CallDepth, "call-depth", 64, 1, 256, "calls", "function calls nested in each other (calls are inlined)"},
    {Limit::RibArray, "rib-array", int64_t{1} << 25, 16, int64_t{1} << 30, "values",
     "numbers or strings in one RIB array"},
    {Limit::RibBytes, "rib-bytes", int64_t{1} << 32, 1024, int64_t{1} << 42, "bytes",
     "bytes of a RIB file or archive, decompressed if gzip-compressed"},
    {Limit::ImagePixels, "image-pixels", int64_t{1} << 28, 1, int64_t{1} << 31, "pixels",
     "pixels of an image rendered, written or read"},
    {Limit::PixelSamples, "pixel-samples", 64, 1, 256, "samples", "samples per pixel along each axis"},
    {Limit::FilmMb, "film-mb", 16384, 1, int64_t{1} << 24, "MiB",
     "memory of the film: every pixel's channels, and the sample counts"},
    {Limit::TimeLimit, "time-limit", 0, 0, int64_t{1} << 40, "seconds",
     "wall-clock time of a render, 0 for none (also --time-limit S)"},
}};

struct Values {
    Values() {
        for (const LimitInfo& info : kTable) value[static_cast<size_t>(info.limit)].store(info.defaultValue);
    }
    std::array<std::atomic<int64_t>, kLimitCount> value;
};

std::atomic<int64_t>& Slot(Limit limit) {
    static Values values;
    return values.value[static_cast<size_t>(limit)];
}

}  // namespace

const LimitInfo& Info(Limit limit) { return kTable[static_cast<size_t>(limit)]; }

const LimitInfo* FindLimit(std::string_view name) {
    for (const LimitInfo& info : kTable)
        if (name == info.name) return &info;
    return nullptr;
}

int64_t LimitValue(Limit limit) { return Slot(limit).load(std::memory_order_relaxed); }

void SetLimit(Limit limit, int64_t value) {
    const LimitInfo& info = Info(limit);
    value = value < info.minValue ? info.minValue : value > info.maxValue ? info.maxValue : value;
    Slot(limit).store(value, std::memory_order_relaxed);
}

void ResetLimits() {
    for (const LimitInfo& info : kTable) SetLimit(info.limit, info.defaultValue);
}

std::optional<std::string> ApplyLimit(std::string_view assignment) {
    const size_t eq = assignment.find('=');
    const std::string_view name = assignment.substr(0, eq);
    const LimitInfo* info = FindLimit(name);
    if (!info) {
        std::string names;
        for (const LimitInfo& i : kTable) names += (names.empty() ? "" : ", ") + std::string(i.name);
        return "unknown limit '" + std::string(name) + "' (limits: " + names + ")";
    }
    if (eq == std::string_view::npos) return "--limit takes NAME=VALUE, as --limit " + std::string(name) + "=N";
    std::string_view text = assignment.substr(eq + 1);
    int64_t scale = 1;
    if (!text.empty()) {
        switch (text.back()) {
            case 'k':
            case 'K': scale = 1000; break;
            case 'M': scale = 1'000'000; break;
            case 'G': scale = 1'000'000'000; break;
            default: break;
        }
        if (scale != 1) text.remove_suffix(1);
    }
    int64_t value = -1;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    const std::string range = std::to_string(info->minValue) + " to " + std::to_string(info->maxValue);
    if (ec != std::errc() || end != text.data() + text.size() || value < 0 || value > info->maxValue / scale ||
        value * scale < info->minValue)
        return "limit " + std::string(info->name) + " takes a whole number from " + range + ", not '" +
               std::string(assignment.substr(eq + 1)) + "'";
    SetLimit(info->limit, value * scale);
    return std::nullopt;
}

std::string LimitNote(Limit limit) {
    const LimitInfo& info = Info(limit);
    return "(limit " + std::string(info.name) + " = " + std::to_string(LimitValue(limit)) + "; raise it with --limit " +
           info.name + "=N)";
}

std::string ReadSourceFile(const std::string& path, std::string* bytes) {
    bytes->clear();
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) return "cannot open file: " + std::generic_category().message(errno);
    const int64_t limit = LimitValue(Limit::SourceBytes);
    auto tooLarge = [&] {
        bytes->clear();
        return "file larger than " + std::to_string(limit) + " bytes " + LimitNote(Limit::SourceBytes);
    };
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size > limit) return tooLarge();
    in.seekg(0, std::ios::beg);
    // Read in pieces (a pipe has no size), stopping one byte past the limit.
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        bytes->append(buffer, static_cast<size_t>(in.gcount()));
        if (static_cast<int64_t>(bytes->size()) > limit) return tooLarge();
    }
    if (in.bad()) return "cannot read file";
    return {};
}

std::string LimitsTable() {
    std::string out = "limit                     value       default     maximum     unit        what it limits\n";
    char line[512];
    for (const LimitInfo& info : kTable) {
        std::snprintf(line, sizeof line, "%-25s %-11lld %-11lld %-11lld %-11s %s\n", info.name,
                      static_cast<long long>(LimitValue(info.limit)), static_cast<long long>(info.defaultValue),
                      static_cast<long long>(info.maxValue), info.unit, info.what);
        out += line;
    }
    out +=
        "Set one with --limit NAME=VALUE (k, M, G suffixes: 250k). Budgets are not limits: past\n"
        "--cache-mb the bound cache evicts, past --texture-mb the texture tiles do, and work goes on.\n";
    return out;
}

}  // namespace affray::diag
