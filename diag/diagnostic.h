// diag/diagnostic.h: the one way affray reports a problem with its input or output.
// Every front end (preprocessor, lexer, parser, compiler, .afb loader and verifier, RIB reader,
// image output, command line) reports Diagnostic values into a Report; library code never
// prints and never exits. The caller prints Report::format(), which gives each message as
//     file:line:col: error: message
// on one line (control characters and stray bytes are escaped, so a message is never split),
// followed by the source line and a caret under the column wherever a source line is known, as
// gcc and clang print them, then the diagnostic's notes in the same form. See docs/design.md
// (decision 7) and the exit codes below.
#pragma once

#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace affray::diag {

enum class Severity { Error, Warning, Note };

/// Where a message points. Lines and columns count from 1; 0 means unknown (a column 0 prints
/// no column, a line 0 neither line nor column). `text` is the source line itself, kept so a
/// diagnostic can show it and a caret after the file is gone; empty when there is none.
struct Location {
    Location() = default;
    Location(std::string file_, int line_ = 0, int column_ = 0, std::string text_ = {})
        : file(std::move(file_)), line(line_), column(column_), text(std::move(text_)) {}

    std::string file;
    int line = 0;
    int column = 0;
    std::string text;
};

struct Diagnostic {
    Severity severity = Severity::Error;
    Location where;
    std::string message;
    /// Notes that explain this diagnostic (e.g. "declared here"), printed after it.
    std::vector<Diagnostic> notes;
};

/// The diagnostic in the one format: its line, the source line and caret if known, its notes.
std::string Format(const Diagnostic& d);

/// `message` printable on one line: control characters and bytes that are not UTF-8 escaped
/// (\n, \r, \xNN); tabs and UTF-8 characters kept.
std::string OneLine(std::string_view message);

/// Line `line` (1-based) of `text` without its line break; empty if out of range.
std::string_view LineOf(std::string_view text, int line);

/// Line `line` of the file at `path`, read from disk; empty if the file cannot be read.
std::string ReadLine(const std::string& path, int line);

/// The diagnostics of one run of a front end, in the order reported.
class Report {
  public:
    void error(Location where, std::string message) {
        add({Severity::Error, std::move(where), std::move(message), {}});
    }
    void warning(Location where, std::string message) {
        add({Severity::Warning, std::move(where), std::move(message), {}});
    }
    /// A note on the last error or warning (a note before any stands alone).
    void note(Location where, std::string message);
    /// A note of its own, attached to no other diagnostic (something skipped on purpose). The
    /// same notice at the same place again is kept once.
    void notice(Location where, std::string message);

    /// Adds `d`. The same error or warning at the same place again (an unrolled loop body, an
    /// inlined function lowered once per call) is kept once, and so are the notes after it.
    /// Past kMaxErrors errors, errors are counted but not kept.
    void add(Diagnostic d);
    void add(const Report& other);

    int errorCount() const { return m_errorCount; }
    bool hasErrors() const { return m_errorCount > 0; }
    bool empty() const { return m_list.empty(); }
    const std::vector<Diagnostic>& all() const { return m_list; }

    /// Every diagnostic in the one format; past kMaxErrors, one closing "too many errors" line
    /// (about the file of the first error not kept).
    std::string format() const;

    static constexpr int kMaxErrors = 50;

  private:
    std::vector<Diagnostic> m_list;
    int m_errorCount = 0;
    std::string m_overflowFile;  // the file of the first error past kMaxErrors
    bool m_repeating = false;    // the last error or warning repeated an earlier one
};

/// Prints report.format(), for logs and test messages.
std::ostream& operator<<(std::ostream& out, const Report& report);

/// The exit status of the `affray` command, documented in the README and tested.
enum ExitCode : int {
    kExitSuccess = 0,
    kExitBadInput = 1,   ///< a shader, scene, compiled shader or image given is unreadable or wrong
    kExitUsage = 2,      ///< the command line is wrong (unknown option, missing argument, ...)
    kExitOutput = 3,     ///< an output file cannot be written (nothing partial is left behind)
    kExitResources = 4,  ///< out of memory
    kExitInternal = 5,   ///< an internal error (a bug in affray; the message says what)
};

}  // namespace affray::diag
