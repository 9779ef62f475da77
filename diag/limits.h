// diag/limits.h: the one table of affray's resource limits. Every input that could make affray
// spend unbounded time or memory (a huge source, an endless loop the compiler would unroll, a
// RIB array of a billion numbers, a film larger than memory) meets one of these limits, and is
// refused *before* the time or memory is spent, with an error that names the limit and says how
// to raise it:
//     loop.sl:3:5: error: this loop runs more than 100000 iterations ... (limit loop-iterations =
//     100000; raise it with --limit loop-iterations=N)
// The values are process-wide (set once from the command line, before any work starts, by
// `--limit NAME=VALUE`; `affray limits` prints the table). Library code reads them with
// LimitValue() and words its error with LimitNote(); tests set them with SetLimit() and put the
// defaults back with ResetLimits().
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace affray::diag {

enum class Limit : int {
    SourceBytes,            ///< bytes of one .sl or .afb file, and of preprocessed text
    IncludeDepth,           ///< #include nesting
    Nesting,                ///< expression and statement nesting, and open brackets
    ProgramOps,             ///< operations a shader may ask for while lowered and unrolled
    LoopIterations,         ///< iterations of a loop whose count is known when it is compiled
    VaryingLoopIterations,  ///< iterations unrolled of a loop whose count varies (then bounded)
    CallDepth,              ///< function calls nested (every call is inlined)
    RibArray,               ///< numbers or strings in one RIB array
    RibBytes,               ///< bytes of a RIB file or archive (decompressed, if gzip-compressed)
    ImagePixels,            ///< pixels of an image written or read (the film, an EXR, a map)
    PixelSamples,           ///< samples per pixel along each axis
    FilmMb,                 ///< MiB of memory for the film (every sample of every channel)
    TimeLimit,              ///< seconds of wall-clock time for a render (0: none)
};
inline constexpr int kLimitCount = static_cast<int>(Limit::TimeLimit) + 1;

struct LimitInfo {
    Limit limit;
    const char* name;  ///< as written on the command line: "loop-iterations"
    int64_t defaultValue;
    int64_t minValue, maxValue;  ///< what --limit accepts
    const char* unit;            ///< "bytes", "iterations", ... for the table
    const char* what;            ///< one line for `affray limits`
};

/// The table entry of `limit`; every Limit has one.
const LimitInfo& Info(Limit limit);
/// The entry named `name`, if any.
const LimitInfo* FindLimit(std::string_view name);

/// The limit's current value.
int64_t LimitValue(Limit limit);
/// Sets the limit (clamped into [minValue, maxValue]). Not for use while work is running.
void SetLimit(Limit limit, int64_t value);
/// Every limit back to its default.
void ResetLimits();

/// Parses and applies "NAME=VALUE" (VALUE a non-negative integer, with an optional k, M or G
/// suffix). Returns an error message, or nothing when it was applied.
std::optional<std::string> ApplyLimit(std::string_view assignment);

/// "(limit NAME = VALUE; raise it with --limit NAME=N)", to end an error message with.
std::string LimitNote(Limit limit);

/// Reads the file at `path` whole into *bytes, refusing it without reading it past the
/// source-bytes limit. Returns "" or the error: "cannot open file: <reason>", "cannot read file",
/// or "file larger than N bytes (limit source-bytes ...)".
std::string ReadSourceFile(const std::string& path, std::string* bytes);

/// The table for `affray limits`: name, value, default, range and what it limits, one per line.
std::string LimitsTable();

}  // namespace affray::diag
