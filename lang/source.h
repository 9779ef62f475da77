// lang/source.h: a source file held in memory, and positions inside it.
// Every stage that reports on user input (lexer, parser, compiler) speaks in these positions, so a
// diagnostic can always show the file, the line and a caret under the offending column.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace affray::lang {

/// A position in a source file. Lines and columns count from 1; 0 means "unknown". `file` says
/// which file: 0 is the file a Diagnostics was made for, others are the files its line markers
/// named (an #include'd header), numbered by Diagnostics::fileIndex.
struct SourceLoc {
    int line = 0;
    int column = 0;
    int file = 0;
};

/// The text of one source file, with an index of its line starts for caret printing.
class SourceFile {
  public:
    SourceFile(std::string path, std::string text);

    /// Reads a file from disk; returns false (leaving *out untouched, and *error, if not null, a
    /// sentence such as "cannot open file: No such file or directory") if it cannot be read.
    static bool Load(const std::string& path, SourceFile* out, std::string* error);

    const std::string& path() const { return m_path; }
    const std::string& text() const { return m_text; }
    int lineCount() const { return static_cast<int>(m_lineStarts.size()); }
    /// The text of line `line` (1-based) without its newline; empty if out of range.
    std::string_view lineText(int line) const;

  private:
    std::string m_path;
    std::string m_text;
    std::vector<size_t> m_lineStarts;
};

}  // namespace affray::lang
