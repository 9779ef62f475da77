// lang/source.cpp: loading source files and finding their lines.
#include "lang/source.h"

#include "diag/limits.h"

namespace affray::lang {

SourceFile::SourceFile(std::string path, std::string text) : m_path(std::move(path)), m_text(std::move(text)) {
    m_lineStarts.push_back(0);
    for (size_t i = 0; i < m_text.size(); ++i)
        if (m_text[i] == '\n' && i + 1 < m_text.size()) m_lineStarts.push_back(i + 1);
}

bool SourceFile::Load(const std::string& path, SourceFile* out, std::string* error) {
    std::string text;
    if (std::string problem = diag::ReadSourceFile(path, &text); !problem.empty()) {
        if (error) *error = std::move(problem);
        return false;
    }
    *out = SourceFile(path, std::move(text));
    return true;
}

std::string_view SourceFile::lineText(int line) const {
    if (line < 1 || line > lineCount()) return {};
    size_t begin = m_lineStarts[line - 1];
    size_t end = m_text.find('\n', begin);
    if (end == std::string::npos) end = m_text.size();
    if (end > begin && m_text[end - 1] == '\r') --end;
    return std::string_view(m_text).substr(begin, end - begin);
}

}  // namespace affray::lang
