// lang/preprocess.cpp: Preprocess(), a thin, safe wrapper around libmcpp.
// mcpp reads its input from a named file, keeps its state in globals and reports through
// print callbacks. So each call: copies the text into a private temporary directory, runs
// mcpp_lib_main under one process-wide mutex with callbacks that capture (and cap) its output,
// then turns mcpp's messages into Diagnostics and its line markers into paths the lexer and
// Diagnostics can open. mcpp never calls exit() (libmcpp imports no exit/abort); its fatal
// errors (#include nested more than 256 deep, output write failure) return from mcpp_lib_main,
// but leave the included files open, and every run leaks a little memory: mcpp's fopen/fclose/
// malloc/realloc/free are redirected here (see lang/CMakeLists.txt), so that what a run leaves
// open or allocated is released after it. One block or so is kept on purpose from one run to the
// next, which frees it when it starts; so memory is released one run late, and at most one run's
// leftovers are ever held. mcpp's memcmp comes here too: it must not read past a mismatch.
#include "lang/preprocess.h"

#include <stdio.h>
#include <stdlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdarg>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <string_view>
#include <unordered_set>
#include <vector>

extern "C" {
#include <mcpp_lib.h>
// mcpp's count of the #include files it is inside (its global.c; not in its public header).
extern int include_nest;
}

#include "diag/limits.h"

namespace affray::lang {

namespace fs = std::filesystem;

namespace {

// Output past this (the source-bytes limit) is a runaway macro or #include; mcpp is stopped by
// a failing write.
size_t MaxOutputBytes() { return static_cast<size_t>(diag::LimitValue(diag::Limit::SourceBytes)); }
constexpr size_t kMaxMessageBytes = size_t{1} << 20;

// Target-CPU macros the compiler-independent mcpp predefines even with -N (it shows __x86_64__
// and __amd64__ on amd64); undefining a name that is not defined is harmless.
constexpr const char* kUndefined[] = {"__MCPP",    "__STDC_HOSTED__", "__x86_64__",   "__amd64__",
                                      "__i386__",  "__aarch64__",     "__arm__",      "__ppc__",
                                      "__ppc64__", "__powerpc__",     "__powerpc64__"};

// --- Capturing mcpp's output ------------------------------------------------------------------

struct Capture {
    std::string out;
    std::string err;
    bool overflow = false;             // output hit MaxOutputBytes(), or memory ran out
    bool tooDeep = false;              // #include nested past the include-depth limit
    int maxDepth = 0;                  // the include-depth limit
    std::vector<FILE*> files;          // that mcpp opened and has not closed
    std::unordered_set<void*> blocks;  // that mcpp allocated and has not freed
};

std::mutex g_mcppMutex;        // mcpp's globals are shared by every caller
Capture* g_capture = nullptr;  // the running call's capture, under g_mcppMutex
// Allocated by the last run and not freed, under the mutex. Freed at exit too: once this set is
// destroyed nothing points at the blocks, and LeakSanitizer would report mcpp's leftovers.
struct Leftovers : std::unordered_set<void*> {
    ~Leftovers() {
        for (void* p : *this) free(p);
    }
};
Leftovers g_leftovers;

// Appends for mcpp; EOF makes mcpp stop with "File write error". No exception may cross mcpp.
int Put(const char* s, size_t n, OUTDEST od) {
    try {
        if (od == OUT) {
            if (g_capture->tooDeep) return EOF;  // stops mcpp, see AffrayMcppFopen
            if (g_capture->overflow || g_capture->out.size() + n > MaxOutputBytes()) {
                g_capture->overflow = true;
                return EOF;
            }
            g_capture->out.append(s, n);
        } else if (g_capture->err.size() + n <= kMaxMessageBytes) {
            g_capture->err.append(s, n);  // and DBG, used only by #pragma MCPP debug
        }
        return 0;
    } catch (...) {
        g_capture->overflow = true;
        return EOF;
    }
}

int CaptureFputc(int c, OUTDEST od) {
    char ch = static_cast<char>(c);
    return Put(&ch, 1, od) == EOF ? EOF : c;
}

int CaptureFputs(const char* s, OUTDEST od) { return Put(s, std::char_traits<char>::length(s), od); }

int CaptureFprintf(OUTDEST od, const char* format, ...) {
    char small[1024];
    va_list args;
    va_start(args, format);
    va_list again;
    va_copy(again, args);
    int n = vsnprintf(small, sizeof small, format, args);
    va_end(args);
    int rc = n;
    if (n < 0) {
        rc = EOF;
    } else if (static_cast<size_t>(n) < sizeof small) {
        if (Put(small, static_cast<size_t>(n), od) == EOF) rc = EOF;
    } else if (static_cast<size_t>(n) <= MaxOutputBytes()) {
        std::unique_ptr<char[]> big(new (std::nothrow) char[static_cast<size_t>(n) + 1]);
        if (!big) {
            rc = EOF;
        } else {
            vsnprintf(big.get(), static_cast<size_t>(n) + 1, format, again);
            if (Put(big.get(), static_cast<size_t>(n), od) == EOF) rc = EOF;
        }
    } else {
        g_capture->overflow = true;
        rc = EOF;
    }
    va_end(again);
    return rc;
}

// Runs mcpp with `args` (without argv[0]) and returns what it printed.
Capture RunMcpp(const std::vector<std::string>& args) {
    std::vector<std::string> storage{"mcpp"};
    storage.insert(storage.end(), args.begin(), args.end());
    std::vector<char*> argv;
    argv.reserve(storage.size() + 1);
    for (std::string& s : storage) argv.push_back(s.data());
    argv.push_back(nullptr);

    Capture capture;
    capture.maxDepth = static_cast<int>(diag::LimitValue(diag::Limit::IncludeDepth));
    std::lock_guard<std::mutex> lock(g_mcppMutex);
    g_capture = &capture;
    mcpp_set_out_func(CaptureFputc, CaptureFputs, CaptureFprintf);
    mcpp_lib_main(static_cast<int>(argv.size()) - 1, argv.data());
    mcpp_reset_def_out_func();
    for (FILE* f : capture.files) fclose(f);
    capture.files.clear();
    for (void* p : g_leftovers) free(p);
    g_leftovers.clear();
    g_leftovers.swap(capture.blocks);
    capture.blocks.clear();
    g_capture = nullptr;
    return capture;
}

// --- The input file ---------------------------------------------------------------------------

/// A fresh private directory holding a copy of the text, removed on destruction.
class TempCopy {
  public:
    TempCopy(const std::string& name, const std::string& text, std::string* error) {
        std::error_code ec;
        fs::path base = fs::temp_directory_path(ec);
        if (ec) base = "/tmp";
        std::string pattern = (base / "affray-pp-XXXXXX").string();
        if (!mkdtemp(pattern.data())) {
            *error = "cannot create a temporary directory for the preprocessor";
            return;
        }
        m_dir = pattern;
        m_file = (m_dir / name).lexically_normal();
        std::ofstream out(m_file, std::ios::binary);
        out << text;
        // mcpp warns about a last line without a newline; a copy can simply have one.
        if (!text.empty() && text.back() != '\n') out << '\n';
        if (!out.flush()) *error = "cannot write a temporary copy for the preprocessor";
    }
    ~TempCopy() {
        std::error_code ec;
        if (!m_dir.empty()) fs::remove_all(m_dir, ec);
    }
    TempCopy(const TempCopy&) = delete;
    TempCopy& operator=(const TempCopy&) = delete;
    const fs::path& file() const { return m_file; }

  private:
    fs::path m_dir;
    fs::path m_file;
};

// --- Files and line markers --------------------------------------------------------------------

/// The files of one Preprocess call: result.files, and their text for placing carets.
class FileTable {
  public:
    FileTable(PreprocessResult& result, const std::string& path, const std::string& text, std::string tempPath)
        : m_result(result), m_tempPath(std::move(tempPath)) {
        m_result.files = {path};
        m_texts.emplace(0, SourceFile(path, text));
    }

    /// The path shown for a file mcpp named: the original path for the temporary copy.
    const std::string& Shown(const std::string& mcppPath) const {
        return mcppPath == m_tempPath ? m_result.files[0] : mcppPath;
    }
    int Index(const std::string& mcppPath) {
        if (mcppPath == m_tempPath) return 0;
        for (size_t i = 1; i < m_result.files.size(); ++i)
            if (m_result.files[i] == mcppPath) return static_cast<int>(i);
        m_result.files.push_back(mcppPath);
        return static_cast<int>(m_result.files.size()) - 1;
    }
    /// The text of a line of file `index` (empty if it cannot be read).
    std::string_view LineText(int index, int line) {
        auto it = m_texts.find(index);
        if (it == m_texts.end()) {
            SourceFile file(m_result.files[index], "");
            SourceFile::Load(m_result.files[index], &file, nullptr);
            it = m_texts.emplace(index, std::move(file)).first;
        }
        return it->second.lineText(line);
    }

  private:
    PreprocessResult& m_result;
    std::string m_tempPath;
    std::map<int, SourceFile> m_texts;
};

std::string Normal(const std::string& path) { return fs::path(path).lexically_normal().string(); }

// Rewrites mcpp's `#line N "name"` markers to name files by absolute path (the original path for
// the main file). mcpp names a file found next to its includer relative to that includer, so keep
// the stack of open files: a marker for line 1 enters a file, a later line of another name returns.
std::string RewriteMarkers(const std::string& out, const FileTable& files) {
    struct Open {
        std::string printed;   // as mcpp wrote it
        std::string absolute;  // resolved
    };
    std::vector<Open> stack;
    std::string result;
    result.reserve(out.size());
    size_t pos = 0;
    while (pos < out.size()) {
        size_t end = out.find('\n', pos);
        if (end == std::string::npos) end = out.size();
        std::string_view line(out.data() + pos, end - pos);
        size_t open = line.find('"');
        size_t close = line.rfind('"');
        if (line.substr(0, 6) == "#line " && open != std::string_view::npos && close > open) {
            long number = std::strtol(std::string(line.substr(6, open - 6)).c_str(), nullptr, 10);
            std::string printed(line.substr(open + 1, close - open - 1));
            if (stack.empty()) {
                stack.push_back({printed, Normal(printed)});
            } else if (number == 1) {
                fs::path name(printed);
                std::string absolute = name.is_absolute()
                                           ? Normal(printed)
                                           : Normal((fs::path(stack.back().absolute).parent_path() / name).string());
                stack.push_back({printed, absolute});
            } else {
                while (stack.size() > 1 && stack.back().printed != printed) stack.pop_back();
            }
            result += "#line " + std::to_string(number) + " \"" + files.Shown(stack.back().absolute) + "\"";
        } else {
            result += line;
        }
        if (end < out.size()) result += '\n';
        pos = end + 1;
    }
    return result;
}

// Turns mcpp's messages (with -j, one line each: "file:line: error: text") into diagnostics.
void AddMessages(const Capture& capture, FileTable& files, PreprocessResult& result) {
    static constexpr struct {
        std::string_view tag;
        Severity severity;
    } kKinds[] = {
        {": fatal error: ", Severity::Error}, {": error: ", Severity::Error}, {": warning: ", Severity::Warning}};
    size_t pos = 0;
    bool reportedDepth = false;
    const std::string& err = capture.err;
    while (pos < err.size()) {
        size_t end = err.find('\n', pos);
        if (end == std::string::npos) end = err.size();
        std::string_view line(err.data() + pos, end - pos);
        pos = end + 1;
        for (const auto& kind : kKinds) {
            size_t at = line.find(kind.tag);
            if (at == std::string_view::npos || at == 0) continue;
            size_t colon = line.rfind(':', at - 1);
            if (colon == std::string_view::npos) continue;
            std::string file(line.substr(0, colon));
            const long parsed = std::strtol(std::string(line.substr(colon + 1, at - colon - 1)).c_str(), nullptr, 10);
            const int number = parsed > 0 && parsed < (1L << 30) ? static_cast<int>(parsed) : 0;
            std::string message(line.substr(at + kind.tag.size()));
            // mcpp reads the locale to guess the source encoding, and warns about names it does
            // not know (C.UTF-8); the encoding does not matter to RSL.
            if (message.rfind("Unknown encoding", 0) == 0) break;
            if (capture.tooDeep && message == "File write error") break;  // reported below
            if (capture.tooDeep && message.rfind("Can't open include file", 0) == 0) {
                if (reportedDepth) break;  // the #includes refused after the first
                reportedDepth = true;
                message = "#include nested more than " + std::to_string(diag::LimitValue(diag::Limit::IncludeDepth)) +
                          " files deep: does a header include itself? " + diag::LimitNote(diag::Limit::IncludeDepth);
            }
            if (capture.overflow && message == "File write error")
                message = "preprocessed text longer than " + std::to_string(MaxOutputBytes()) +
                          " bytes: is a macro or #include expanding without end? " +
                          diag::LimitNote(diag::Limit::SourceBytes);
            // mcpp gives no column: point at the line's first non-blank character.
            const int index = files.Index(Normal(file));
            diag::Diagnostic d{kind.severity,
                               {result.files[static_cast<size_t>(index)], number > 0 ? number : 0, 0, {}},
                               std::move(message),
                               {}};
            if (d.where.line > 0) {
                std::string_view text = files.LineText(index, d.where.line);
                const size_t first = text.find_first_not_of(" \t\f\v");
                if (first != std::string_view::npos) d.where.column = static_cast<int>(first) + 1;
                d.where.text = std::string(text);
            }
            result.errors.push_back(std::move(d));
            break;
        }
    }
}

}  // namespace

// mcpp's fopen and fclose (renamed in its library by objcopy): they keep Capture::files, so that
// RunMcpp can close what a fatal error left open. mcpp only runs under g_mcppMutex.
// mcpp's own count of nested #includes (its global `include_nest`) is the include depth; mcpp
// closes and later reopens outer files when many are nested, so open files do not count it.
// Past the include-depth limit the open of a new #include fails (mcpp reports "Can't open include
// file" at the #include, which AddMessages rewords), and so do every later open and every later
// write of output, which stops mcpp within one pass over the files it is inside: a header that includes itself twice would otherwise take 2^depth
// steps before mcpp's own 256-deep limit is ever reached.
extern "C" FILE* AffrayMcppFopen(const char* path, const char* mode) {
    if (g_capture && (g_capture->tooDeep || include_nest > g_capture->maxDepth)) {
        g_capture->tooDeep = true;
        errno = ENOENT;  // as if absent: mcpp takes EMFILE as a cue to close and reopen outer files
        return nullptr;
    }
    FILE* f = fopen(path, mode);
    if (!f || !g_capture) return f;
    try {
        g_capture->files.push_back(f);
    } catch (...) {
        fclose(f);
        return nullptr;
    }
    return f;
}

extern "C" int AffrayMcppFclose(FILE* f) {
    if (g_capture) std::erase(g_capture->files, f);
    return fclose(f);
}

// mcpp's own xmalloc reports a failure (null) as a fatal error.
extern "C" void* AffrayMcppMalloc(size_t size) {
    void* p = malloc(size);
    if (!p || !g_capture) return p;
    try {
        g_capture->blocks.insert(p);
    } catch (...) {
        free(p);
        return nullptr;
    }
    return p;
}

extern "C" void* AffrayMcppRealloc(void* old, size_t size) {
    // glibc's realloc(p, 0) frees p and returns null, which mcpp's xrealloc takes for success
    // (a null result is an error only for a nonzero size): p would stay tracked, and be freed
    // again. A one-byte block keeps every pointer mcpp holds valid and tracked.
    if (size == 0) size = 1;
    if (!g_capture) return realloc(old, size);
    // Reserve the set entry first, so that a failure leaves `old` valid and tracked.
    try {
        g_capture->blocks.reserve(g_capture->blocks.size() + 1);
    } catch (...) {
        return nullptr;
    }
    void* p = realloc(old, size);
    if (p) {
        if (g_capture->blocks.erase(old) == 0) g_leftovers.erase(old);
        g_capture->blocks.insert(p);
    }
    return p;
}

extern "C" void AffrayMcppFree(void* p) {
    if (g_capture && g_capture->blocks.erase(p) == 0) g_leftovers.erase(p);
    free(p);
}

// mcpp's memcmp: mcpp looks a name up in its macro table (look_prev) with memcmp over the name's
// whole length, against names in the table that may be shorter (their NUL differs, and their
// allocation ends soon after). The result is decided at the first differing byte, so stop
// there: bytes past it are never read.
extern "C" int AffrayMcppMemcmp(const void* a, const void* b, size_t n) {
    const auto* x = static_cast<const unsigned char*>(a);
    const auto* y = static_cast<const unsigned char*>(b);
    for (size_t i = 0; i < n; ++i)
        if (x[i] != y[i]) return x[i] < y[i] ? -1 : 1;
    return 0;
}

PreprocessResult Preprocess(const std::string& path, const std::string& text, const PreprocessOptions& options) {
    PreprocessResult result;
    result.files = {path};
    auto fail = [&](std::string message) {
        result.errors.push_back({Severity::Error, {path, 0, 0, {}}, std::move(message), {}});
        return result;
    };
    if (text.size() > MaxOutputBytes())
        return fail("file larger than " + std::to_string(MaxOutputBytes()) + " bytes " +
                    diag::LimitNote(diag::Limit::SourceBytes));

    std::string error;
    std::string name = fs::path(path).filename().string();
    TempCopy copy(name.empty() || name == "." || name == ".." ? "input.sl" : name, text, &error);
    if (!error.empty()) return fail(error);
    const std::string tempPath = copy.file().string();

    // Standard C99 mode (variadic macros), no system include directories, no non-standard
    // predefined macros, whitespace and columns kept (-k), one line per message (-j).
    std::vector<std::string> args = {"-N", "-I-", "-k", "-j", "-V199901L"};
    for (const char* macro : kUndefined) args.insert(args.end(), {"-U", macro});
    std::error_code ec;
    fs::path home = fs::absolute(fs::path(path), ec).parent_path();
    if (!ec) args.insert(args.end(), {"-I", home.empty() ? "." : home.string()});
    for (const std::string& dir : options.includeDirs)
        if (!dir.empty()) args.insert(args.end(), {"-I", dir});
    for (const std::string& define : options.defines) {
        if (define.empty() || define[0] == '=' || define[0] == '-')
            return fail("invalid macro definition '-D " + define + "'");
        args.insert(args.end(), {"-D", define});
    }
    args.push_back(tempPath);

    Capture capture = RunMcpp(args);

    FileTable files(result, path, text, tempPath);
    AddMessages(capture, files, result);
    if (capture.overflow && result.errors.empty())
        fail("preprocessed text longer than " + std::to_string(MaxOutputBytes()) + " bytes " +
             diag::LimitNote(diag::Limit::SourceBytes));
    if (capture.tooDeep && std::none_of(result.errors.begin(), result.errors.end(),
                                        [](const diag::Diagnostic& d) { return d.severity == Severity::Error; }))
        fail("#include nested more than " + std::to_string(diag::LimitValue(diag::Limit::IncludeDepth)) +
             " files deep " + diag::LimitNote(diag::Limit::IncludeDepth));
    result.text = RewriteMarkers(capture.out, files);
    // __FILE__ expands to the copy's name; show the original instead.
    const std::string quotedTemp = "\"" + tempPath + "\"";
    for (size_t at = result.text.find(quotedTemp); at != std::string::npos;
         at = result.text.find(quotedTemp, at + path.size() + 2))
        result.text.replace(at, quotedTemp.size(), "\"" + path + "\"");

    result.ok = true;
    for (const diag::Diagnostic& d : result.errors)
        if (d.severity == Severity::Error) result.ok = false;
    return result;
}

}  // namespace affray::lang
