// lang/diagnostics.h: errors and warnings about user input, collected as values.
// Library code never prints or exits: it reports here, and the caller decides what to show.
// The one message format is   file:line:col: error: message   followed by the source line and a
// caret under the column, as gcc and clang print it.
// A Diagnostics is made for one main file; after preprocessing, locations may also be in the files
// it included (SourceLoc::file), whose text is read from disk only to format a diagnostic there.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "lang/source.h"

namespace affray::lang {

enum class Severity { Error, Warning, Note };

struct Diagnostic {
    Severity severity = Severity::Error;
    SourceLoc loc;
    std::string message;
};

class Diagnostics {
  public:
    /// Diagnostics about `file`; the file must outlive this object.
    explicit Diagnostics(const SourceFile& file) : m_file(&file) {}

    void error(SourceLoc loc, std::string message);
    void warning(SourceLoc loc, std::string message);
    void note(SourceLoc loc, std::string message);

    int errorCount() const { return m_errorCount; }
    bool hasErrors() const { return m_errorCount > 0; }
    const std::vector<Diagnostic>& all() const { return m_list; }
    const SourceFile& file() const { return *m_file; }

    /// The SourceLoc::file index for `path`: 0 for file().path(); another path gets the next
    /// index on first use. Never reads the file.
    int fileIndex(const std::string& path);
    /// The path for a SourceLoc::file index; an index never handed out means the main file.
    const std::string& filePath(int index) const;

    /// All diagnostics in the order reported, each as "file:line:col: kind: message", the source
    /// line and a caret line. Past kMaxErrors errors, one "too many errors" line closes the list.
    std::string format() const;
    /// One diagnostic in the same format.
    std::string format(const Diagnostic& d) const;

    static constexpr int kMaxErrors = 50;

  private:
    /// A file other than the main one, named by a line marker; `text` is loaded on first need.
    struct OtherFile {
        std::string path;
        mutable std::shared_ptr<const SourceFile> text;
        mutable bool loadTried = false;
    };

    void add(Severity severity, SourceLoc loc, std::string message);
    /// The text of line `line` of file `index` (empty if unknown or unreadable).
    std::string_view lineText(int index, int line) const;

    const SourceFile* m_file;
    std::vector<OtherFile> m_others;  // file index i > 0 is m_others[i - 1]
    std::vector<Diagnostic> m_list;
    int m_errorCount = 0;
    bool m_repeating = false;  // the last error or warning repeated an earlier one
};

}  // namespace affray::lang
