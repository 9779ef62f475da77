// lang/preprocess.h: the C preprocessor in front of the lexer (#include, #define, #if ...).
// RSL is preprocessed by the C preprocessor; this runs mcpp (Debian's libmcpp) in its Standard
// C mode, with no system include directories and no compiler-specific predefined macros, and
// returns its output with line markers (#line N "file") that the lexer follows back to the
// original files. Diagnostics are returned as values, never printed.
#pragma once

#include <string>
#include <vector>

#include "lang/diagnostics.h"

namespace affray::lang {

struct PreprocessOptions {
    std::vector<std::string> includeDirs;  // -I DIR, searched after the includer's own directory
    std::vector<std::string> defines;      // -D NAME or -D NAME=VALUE
};

struct PreprocessResult {
    /// No diagnostic in `errors` is an error (warnings may be there).
    bool ok = false;
    /// The preprocessed text, with `#line N "file"` markers naming `files` entries.
    std::string text;
    /// The files the text's line markers name: files[0] is the `path` given to Preprocess, the
    /// others are included files (absolute paths).
    std::vector<std::string> files;
    /// mcpp's errors and warnings, in the order reported, each at a line of an original file
    /// (column: the line's first non-blank character, as mcpp gives no column; an error about the
    /// run itself names `path` with no line).
    std::vector<diag::Diagnostic> errors;
};

/// Preprocesses `text` (the contents of the file at `path`; a quoted #include is looked up next to
/// `path` first). Never prints, never crashes or hangs on bad input: unterminated #if, a missing
/// or recursive #include and garbage all become errors. Thread-safe: mcpp has global state, so
/// calls from several threads take turns.
PreprocessResult Preprocess(const std::string& path, const std::string& text, const PreprocessOptions& options);

}  // namespace affray::lang
