// lang/diagnostics.h: the shading-language front end's view of diag::Report.
// The preprocessor, lexer, parser and compiler speak in SourceLoc (a line, a column and a small
// file index, cheap to keep in every AST node); a Diagnostics turns each into the one
// diag::Diagnostic (diag/diagnostic.h), with the file's path and the source line for the caret.
// A Diagnostics is made for one main file; after preprocessing, locations may also be in the files
// it included (SourceLoc::file), whose text is read from disk only when a diagnostic points there.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "diag/diagnostic.h"
#include "lang/source.h"

namespace affray::lang {

using diag::Severity;

class Diagnostics {
  public:
    /// Diagnostics about `file`; the file must outlive this object.
    explicit Diagnostics(const SourceFile& file) : m_file(&file) {}

    void error(SourceLoc loc, std::string message) { m_report.error(at(loc), std::move(message)); }
    void warning(SourceLoc loc, std::string message) { m_report.warning(at(loc), std::move(message)); }
    void note(SourceLoc loc, std::string message) { m_report.note(at(loc), std::move(message)); }
    /// A diagnostic already in the one form (the preprocessor's), by the path it names.
    void add(diag::Diagnostic d) { m_report.add(std::move(d)); }

    int errorCount() const { return m_report.errorCount(); }
    bool hasErrors() const { return m_report.hasErrors(); }
    const diag::Report& report() const { return m_report; }
    const SourceFile& file() const { return *m_file; }

    /// The SourceLoc::file index for `path`: 0 for file().path(); another path gets the next
    /// index on first use. Never reads the file.
    int fileIndex(const std::string& path);
    /// The path for a SourceLoc::file index; an index never handed out means the main file.
    const std::string& filePath(int index) const;
    /// The location `loc` names, with its source line.
    diag::Location at(SourceLoc loc) const;

    /// All diagnostics in the one format (diag::Report::format).
    std::string format() const { return m_report.format(); }

    static constexpr int kMaxErrors = diag::Report::kMaxErrors;

  private:
    /// A file other than the main one, named by a line marker; `text` is loaded on first need.
    struct OtherFile {
        std::string path;
        mutable std::shared_ptr<const SourceFile> text;
        mutable bool loadTried = false;
    };

    /// The text of line `line` of file `index` (empty if unknown or unreadable).
    std::string_view lineText(int index, int line) const;

    const SourceFile* m_file;
    std::vector<OtherFile> m_others;  // file index i > 0 is m_others[i - 1]
    diag::Report m_report;
};

}  // namespace affray::lang
