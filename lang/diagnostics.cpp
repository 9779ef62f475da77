// lang/diagnostics.cpp: shading-language locations as diag::Location, with their source lines.
#include "lang/diagnostics.h"

namespace affray::lang {

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

diag::Location Diagnostics::at(SourceLoc loc) const {
    diag::Location where{filePath(loc.file), loc.line, loc.line > 0 ? loc.column : 0, {}};
    if (loc.line > 0) where.text = std::string(lineText(loc.file, loc.line));
    return where;
}

}  // namespace affray::lang
