// lang/diagnostics.h: errors and warnings about user input, collected as values.
// Library code never prints or exits: it reports here, and the caller decides what to show.
// The one message format is   file:line:col: error: message   followed by the source line and a
// caret under the column, as gcc and clang print it.
#pragma once

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

    /// All diagnostics in the order reported, each as "file:line:col: kind: message", the source
    /// line and a caret line. Past kMaxErrors errors, one "too many errors" line closes the list.
    std::string format() const;
    /// One diagnostic in the same format.
    std::string format(const Diagnostic& d) const;

    static constexpr int kMaxErrors = 50;

  private:
    void add(Severity severity, SourceLoc loc, std::string message);

    const SourceFile* m_file;
    std::vector<Diagnostic> m_list;
    int m_errorCount = 0;
};

}  // namespace affray::lang
