// diag/diagnostic.cpp: collecting diagnostics and printing them in the one format.
#include "diag/diagnostic.h"

#include <algorithm>
#include <fstream>
#include <ostream>

namespace affray::diag {

namespace {

/// The length of the valid UTF-8 sequence of two to four bytes at text[i], or 0 if there is none.
size_t Utf8Length(std::string_view text, size_t i) {
    const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char lead = byte(i);
    size_t n = lead >= 0xf0 && lead <= 0xf4 ? 4 : lead >= 0xe0 ? 3 : lead >= 0xc2 && lead <= 0xdf ? 2 : 0;
    if (n == 0 || i + n > text.size()) return 0;
    for (size_t k = 1; k < n; ++k)
        if ((byte(i + k) & 0xc0) != 0x80) return 0;
    // No overlong three- and four-byte forms, no surrogates, nothing past U+10FFFF.
    const unsigned char second = byte(i + 1);
    if ((lead == 0xe0 && second < 0xa0) || (lead == 0xed && second >= 0xa0) || (lead == 0xf0 && second < 0x90) ||
        (lead == 0xf4 && second >= 0x90))
        return 0;
    return n;
}

/// Appends `text` to *out printable on one line: control characters and bytes that are not
/// UTF-8 escaped (\n, \r, \xNN), tabs kept. If `caret` is not null, it gets the blank space as
/// wide as the first `bytes` bytes of `text` as printed (tabs kept, one space per character).
void Escape(std::string_view text, std::string* out, size_t bytes = 0, std::string* caret = nullptr) {
    static const char kHex[] = "0123456789abcdef";
    for (size_t i = 0; i < text.size();) {
        const auto u = static_cast<unsigned char>(text[i]);
        size_t n = 1;
        std::string shown;
        if (u >= 0x80 && (n = Utf8Length(text, i)) > 0) {
            shown = std::string(text.substr(i, n));
        } else if ((u >= 0x20 && u < 0x7f) || u == '\t') {
            n = 1;
            shown = std::string(1, text[i]);
        } else {
            n = 1;
            shown = u == '\n' ? "\\n" : u == '\r' ? "\\r" : std::string("\\x") + kHex[u >> 4] + kHex[u & 15];
        }
        if (caret && i < bytes)
            *caret += shown == "\t" ? "\t" : std::string(u >= 0x80 && n > 1 ? 1 : shown.size(), ' ');
        *out += shown;
        i += n;
    }
}

}  // namespace

std::string OneLine(std::string_view message) {
    std::string out;
    out.reserve(message.size());
    Escape(message, &out);
    return out;
}

std::string_view LineOf(std::string_view text, int line) {
    if (line < 1) return {};
    size_t start = 0;
    for (int i = 1; i < line; ++i) {
        start = text.find('\n', start);
        if (start == std::string_view::npos) return {};
        ++start;
    }
    if (start > text.size()) return {};
    size_t end = text.find('\n', start);
    std::string_view l = text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    return l;
}

std::string ReadLine(const std::string& path, int line) {
    if (line < 1 || path.empty()) return {};
    std::ifstream in(path, std::ios::binary);
    std::string text;
    for (int i = 0; i < line; ++i)
        if (!std::getline(in, text)) return {};
    if (!text.empty() && text.back() == '\r') text.pop_back();
    return text;
}

std::string Format(const Diagnostic& d) {
    static const char* const kKind[] = {"error", "warning", "note"};
    const Location& at = d.where;
    std::string out = at.file.empty() ? "affray" : OneLine(at.file);
    if (at.line > 0) {
        out += ":" + std::to_string(at.line);
        if (at.column > 0) out += ":" + std::to_string(at.column);
    }
    out += ": ";
    out += kKind[static_cast<int>(d.severity)];
    out += ": " + OneLine(d.message) + "\n";
    if (at.line > 0 && !at.text.empty()) {
        // The caret goes under the column's byte as printed: escaped bytes before it widen the
        // line, a UTF-8 character is one column, and tabs stay tabs so that it lines up under
        // tab-indented code.
        std::string line, caret;
        Escape(at.text, &line, at.column > 0 ? static_cast<size_t>(at.column - 1) : 0, &caret);
        out += "    " + line + "\n";
        if (at.column > 0) out += "    " + caret + "^\n";
    }
    for (const Diagnostic& n : d.notes) out += Format(n);
    return out;
}

void Report::note(Location where, std::string message) {
    if (m_repeating) return;  // a note on a repeated diagnostic was kept the first time
    Diagnostic n{Severity::Note, std::move(where), std::move(message), {}};
    if (!m_list.empty() && m_list.back().severity != Severity::Note)
        m_list.back().notes.push_back(std::move(n));
    else
        m_list.push_back(std::move(n));
}

void Report::notice(Location where, std::string message) {
    Diagnostic n{Severity::Note, std::move(where), std::move(message), {}};
    for (const Diagnostic& e : m_list)
        if (e.severity == Severity::Note && e.where.line == n.where.line && e.where.column == n.where.column &&
            e.where.file == n.where.file && e.message == n.message)
            return;
    m_repeating = false;
    m_list.push_back(std::move(n));
}

void Report::add(Diagnostic d) {
    if (d.severity == Severity::Note) {
        note(std::move(d.where), std::move(d.message));
        return;
    }
    m_repeating = false;
    for (const Diagnostic& e : m_list)
        if (e.severity == d.severity && e.where.line == d.where.line && e.where.column == d.where.column &&
            e.where.file == d.where.file && e.message == d.message)
            m_repeating = true;
    if (m_repeating) return;  // (an error repeated was counted the first time)
    if (d.severity == Severity::Error) {
        // Past the limit, keep counting (so callers still fail) but stop storing: a cascade of
        // errors after the first few helps nobody. The notes of an error not kept go too.
        if (++m_errorCount > kMaxErrors) {
            if (m_errorCount == kMaxErrors + 1) m_overflowFile = d.where.file.empty() ? "affray" : d.where.file;
            m_repeating = true;
            return;
        }
    }
    m_list.push_back(std::move(d));
}

void Report::add(const Report& other) {
    for (const Diagnostic& d : other.m_list) {
        Diagnostic copy = d;
        std::vector<Diagnostic> notes = std::move(copy.notes);
        copy.notes.clear();
        if (copy.severity == Severity::Note)
            notice(std::move(copy.where), std::move(copy.message));  // a notice stays on its own
        else
            add(std::move(copy));
        for (Diagnostic& n : notes) note(std::move(n.where), std::move(n.message));
    }
    // Errors past the other's limit were counted there but not kept: count them here too.
    const int dropped = other.m_errorCount - std::min(other.m_errorCount, Report::kMaxErrors);
    if (dropped > 0 && m_overflowFile.empty()) m_overflowFile = other.m_overflowFile;
    m_errorCount += dropped;
}

std::string Report::format() const {
    std::string out;
    for (const Diagnostic& d : m_list) out += Format(d);
    if (m_errorCount > kMaxErrors)
        out += OneLine(m_overflowFile.empty() ? "affray" : m_overflowFile) + ": error: too many errors (" +
               std::to_string(m_errorCount) + "), stopping after " + std::to_string(kMaxErrors) + "\n";
    return out;
}

std::ostream& operator<<(std::ostream& out, const Report& report) { return out << report.format(); }

}  // namespace affray::diag
