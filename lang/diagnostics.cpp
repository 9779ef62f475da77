// lang/diagnostics.cpp: formatting diagnostics with the source line and a caret.
#include "lang/diagnostics.h"

namespace affray::lang {

void Diagnostics::error(SourceLoc loc, std::string message) { add(Severity::Error, loc, std::move(message)); }
void Diagnostics::warning(SourceLoc loc, std::string message) { add(Severity::Warning, loc, std::move(message)); }
void Diagnostics::note(SourceLoc loc, std::string message) { add(Severity::Note, loc, std::move(message)); }

void Diagnostics::add(Severity severity, SourceLoc loc, std::string message) {
    // The same error or warning at the same place again (an unrolled loop body or an inlined
    // function lowered once per iteration or call) is reported once; so are the notes after it.
    if (severity != Severity::Note) {
        m_repeating = false;
        for (const Diagnostic& d : m_list)
            if (d.severity == severity && d.loc.line == loc.line && d.loc.column == loc.column &&
                d.loc.file == loc.file && d.message == message)
                m_repeating = true;
    }
    if (m_repeating) return;  // (an error repeated was counted the first time)
    if (severity == Severity::Error) {
        // Past the limit, keep counting (so callers still fail) but stop storing: a cascade of
        // errors after the first few helps nobody.
        if (++m_errorCount > kMaxErrors) return;
    }
    m_list.push_back({severity, loc, std::move(message)});
}

int Diagnostics::fileIndex(const std::string& path) {
    if (path == m_file->path()) return 0;
    for (size_t i = 0; i < m_others.size(); ++i)
        if (m_others[i].path == path) return static_cast<int>(i) + 1;
    m_others.push_back({path, nullptr, false});
    return static_cast<int>(m_others.size());
}

const std::string& Diagnostics::filePath(int index) const {
    if (index < 1 || index > static_cast<int>(m_others.size())) return m_file->path();
    return m_others[index - 1].path;
}

std::string_view Diagnostics::lineText(int index, int line) const {
    if (index < 1 || index > static_cast<int>(m_others.size())) return m_file->lineText(line);
    const OtherFile& other = m_others[index - 1];
    if (!other.loadTried) {
        // An unreadable file (deleted since, or never on disk) just shows no source line.
        other.loadTried = true;
        auto loaded = std::make_shared<SourceFile>(other.path, "");
        if (SourceFile::Load(other.path, loaded.get(), nullptr)) other.text = std::move(loaded);
    }
    return other.text ? other.text->lineText(line) : std::string_view();
}

std::string Diagnostics::format(const Diagnostic& d) const {
    static const char* const kKind[] = {"error", "warning", "note"};
    std::string out = filePath(d.loc.file);
    if (d.loc.line > 0) {
        out += ":" + std::to_string(d.loc.line);
        if (d.loc.column > 0) out += ":" + std::to_string(d.loc.column);
    }
    out += ": ";
    out += kKind[static_cast<int>(d.severity)];
    out += ": " + d.message + "\n";
    std::string_view line = lineText(d.loc.file, d.loc.line);
    if (d.loc.line > 0 && !line.empty()) {
        out += "    ";
        out += line;
        out += "\n    ";
        // Keep tabs in the caret line so the caret lines up under tab-indented code.
        for (int i = 1; i < d.loc.column && i <= static_cast<int>(line.size()); ++i)
            out += line[i - 1] == '\t' ? '\t' : ' ';
        out += "^\n";
    }
    return out;
}

std::string Diagnostics::format() const {
    std::string out;
    for (const Diagnostic& d : m_list) out += format(d);
    if (m_errorCount > kMaxErrors)
        out += m_file->path() + ": error: too many errors (" + std::to_string(m_errorCount) + "), stopping after " +
               std::to_string(kMaxErrors) + "\n";
    return out;
}

}  // namespace affray::lang
