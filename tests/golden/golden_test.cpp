// tests/golden/golden_test.cpp: the golden cases of tests/golden/ (see README.md there). A case is
// NAME.sl or NAME.rib whose first line says how to run it ("// golden: eval --at 0.5,0.5"): the
// words after "golden:" are the `affray` arguments, with the case's file inserted after the
// subcommand. NAME.expected holds the command line, stdout, stderr and the exit status, exactly.
// Each case is a test case of its own ("golden: NAME.sl", tagged [golden][case]), registered at
// start-up from the directory, so a new case needs no code. With AFFRAY_GOLDEN_UPDATE=1 in the
// environment a case writes its NAME.expected from the current output instead of comparing:
// tools/golden.sh runs the cases (and with --update rewrites the .expected files) through this
// file, which is the one place the text is built.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace {

// The suite is meant to cover every diagnostic; far fewer cases means files went missing.
constexpr size_t kMinCases = 60;
// A case that hangs fails instead of hanging the suite (the slowest case takes about 2 s).
constexpr unsigned kTimeoutSeconds = 120;

fs::path GoldenDir() { return fs::path(affray::test::SourceDir()) / "tests" / "golden"; }

/// The cases in `dir`: its .sl and .rib files (subdirectories hold their includes and shaders),
/// sorted by name.
std::vector<fs::path> ListCases(const fs::path& dir) {
    std::vector<fs::path> cases;
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
        const fs::path& p = entry.path();
        if (entry.is_regular_file() && (p.extension() == ".sl" || p.extension() == ".rib")) cases.push_back(p);
    }
    std::sort(cases.begin(), cases.end());
    return cases;
}

fs::path ExpectedPath(const fs::path& file) { return fs::path(file).replace_extension(".expected"); }

/// The words after "golden:" on the first line of `text`; nullopt if it has no such header.
std::optional<std::vector<std::string>> HeaderArgs(const std::string& text) {
    const std::string first = text.substr(0, text.find('\n'));
    const size_t at = first.find("golden:");
    if (at == std::string::npos) return std::nullopt;
    std::istringstream words(first.substr(at + 7));
    std::vector<std::string> args;
    for (std::string w; words >> w;) args.push_back(w);
    if (args.empty()) return std::nullopt;
    return args;
}

/// The arguments that run case `fileName` (relative to its directory): the header's subcommand,
/// the file, the header's other words; render also gets `-o TMP/NAME.exr` unless the header has
/// an -o, so that no image is written into the source tree.
std::vector<std::string> CommandFor(const std::string& fileName, const std::vector<std::string>& header,
                                    const fs::path& tmp) {
    std::vector<std::string> args = {header[0], fileName};
    args.insert(args.end(), header.begin() + 1, header.end());
    if (header[0] == "render" && std::find(header.begin(), header.end(), "-o") == header.end())
        args.insert(args.end(), {"-o", (tmp / fs::path(fileName).replace_extension(".exr")).string()});
    return args;
}

std::string ReplaceAll(std::string text, const std::string& from, const std::string& to) {
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

/// What a run of `affray` printed, and how it ended.
struct Outcome {
    std::string out, err;
    std::string status;  // "exit N", or "killed by signal N"
};

/// Runs `affray args...` in `cwd` with stdout and stderr captured in files under `tmp`. The
/// program is run directly (no shell), so the header's words need no quoting.
Outcome Spawn(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& tmp) {
    const std::string program = AFFRAY_CLI, outPath = (tmp / "stdout").string(), errPath = (tmp / "stderr").string();
    const std::string dir = cwd.string();
    std::vector<char*> argv = {const_cast<char*>(program.c_str())};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        // Only async-signal-safe calls between fork and exec; the alarm survives the exec.
        const int out = open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        const int err = open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (out < 0 || err < 0 || chdir(dir.c_str()) != 0 || dup2(out, 1) < 0 || dup2(err, 2) < 0) _exit(127);
        alarm(kTimeoutSeconds);
        execv(argv[0], argv.data());
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) REQUIRE(errno == EINTR);
    Outcome o{affray::test::ReadText(outPath), affray::test::ReadText(errPath), ""};
    o.status = WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                                 : "killed by signal " + std::to_string(WTERMSIG(status));
    return o;
}

/// What `affray` prints for the case `file`, in the .expected format: "$ affray ARGS", stdout,
/// "--- stderr" and stderr if there is any, "--- STATUS".
/// The temporary directory shows as $TMP and the case's directory is cut from paths (the
/// preprocessor names included files by absolute path). Sets *problem if the case cannot run.
std::string Actual(const fs::path& file, const fs::path& tmp, std::string* problem) {
    const std::optional<std::vector<std::string>> header = HeaderArgs(affray::test::ReadText(file));
    if (!header) {
        *problem = file.filename().string() + ": the first line has no \"golden: SUBCOMMAND ARGS...\" header";
        return "";
    }
    const fs::path dir = fs::canonical(file.parent_path());
    const std::vector<std::string> args = CommandFor(file.filename().string(), *header, tmp);
    const Outcome o = Spawn(args, dir, tmp);
    std::string text = "$ affray";
    for (const std::string& a : args) text += " " + a;
    text += "\n" + o.out;
    if (!o.err.empty()) text += "--- stderr\n" + o.err;
    text += "--- " + o.status + "\n";
    text = ReplaceAll(text, tmp.string(), "$TMP");
    return ReplaceAll(text, dir.string() + "/", "");
}

std::vector<std::string> Lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    if (!text.empty() && text.back() != '\n') lines.back() += "\\ (no newline at end)";
    return lines;
}

/// "" if `actual` equals `expected`, else a unified diff of their lines (expected '-', actual
/// '+', 3 lines of context), from a longest common subsequence.
std::string Mismatch(const std::string& expected, const std::string& actual) {
    if (expected == actual) return "";
    const std::vector<std::string> a = Lines(expected), b = Lines(actual);
    const size_t n = a.size(), m = b.size();
    // lcs[i][j]: the longest common subsequence of a[i..] and b[j..].
    std::vector<std::vector<int>> lcs(n + 1, std::vector<int>(m + 1, 0));
    for (size_t i = n; i-- > 0;)
        for (size_t j = m; j-- > 0;)
            lcs[i][j] = a[i] == b[j] ? lcs[i + 1][j + 1] + 1 : std::max(lcs[i + 1][j], lcs[i][j + 1]);
    struct Op {
        char kind;    // ' ', '-' or '+'
        size_t i, j;  // lines of a and b before this op
        const std::string* line;
    };
    std::vector<Op> ops;
    size_t i = 0, j = 0;
    while (i < n || j < m) {
        if (i < n && j < m && a[i] == b[j])
            ops.push_back({' ', i, j, &a[i]}), ++i, ++j;
        else if (i < n && (j == m || lcs[i + 1][j] >= lcs[i][j + 1]))
            ops.push_back({'-', i, j, &a[i]}), ++i;
        else
            ops.push_back({'+', i, j, &b[j]}), ++j;
    }
    if (std::all_of(ops.begin(), ops.end(), [](const Op& op) { return op.kind == ' '; }))
        return "(the texts differ only in their line endings)\n";
    std::string out = "--- expected\n+++ actual\n";
    constexpr size_t kContext = 3;
    std::vector<size_t> changes;
    for (size_t k = 0; k < ops.size(); ++k)
        if (ops[k].kind != ' ') changes.push_back(k);
    for (size_t c = 0; c < changes.size();) {
        // One hunk: changes less than 2 * kContext unchanged lines apart, with kContext lines of
        // context around them.
        size_t last = c;
        while (last + 1 < changes.size() && changes[last + 1] - changes[last] <= 2 * kContext + 1) ++last;
        const size_t begin = changes[c] >= kContext ? changes[c] - kContext : 0;
        const size_t end = std::min(ops.size(), changes[last] + 1 + kContext);
        size_t aCount = 0, bCount = 0;
        for (size_t t = begin; t < end; ++t) {
            aCount += ops[t].kind != '+';
            bCount += ops[t].kind != '-';
        }
        out += "@@ -" + std::to_string(ops[begin].i + 1) + "," + std::to_string(aCount) + " +" +
               std::to_string(ops[begin].j + 1) + "," + std::to_string(bCount) + " @@\n";
        for (size_t t = begin; t < end; ++t) out += ops[t].kind + *ops[t].line + "\n";
        c = last + 1;
    }
    return out;
}

/// Whether the cases write their .expected files instead of checking them (AFFRAY_GOLDEN_UPDATE=1,
/// as tools/golden.sh --update sets it).
bool UpdateMode() {
    const char* update = std::getenv("AFFRAY_GOLDEN_UPDATE");
    return update && std::string(update) == "1";
}

/// Runs one case and fails with its diff if its output is not the expected one; in UpdateMode,
/// writes the output as the expected one.
void CheckCase(const fs::path& file) {
    const fs::path expected = ExpectedPath(file);
    INFO("golden case tests/golden/" << file.filename().string()
                                     << " (tools/golden.sh --update rewrites the .expected files)");
    const bool update = UpdateMode();
    if (!update && !fs::exists(expected)) FAIL("no " << expected.filename().string() << " beside the case");
    affray::test::TempDir tmp;
    std::string problem;
    const std::string actual = Actual(file, fs::path(tmp.Path("stdout")).parent_path(), &problem);
    if (!problem.empty()) FAIL(problem);
    if (update) {
        std::ofstream out(expected, std::ios::binary);
        out << actual;
        out.close();
        if (!out) FAIL("cannot write " << expected.string());
        return;
    }
    const std::string diff = Mismatch(affray::test::ReadText(expected), actual);
    if (!diff.empty()) FAIL("the output differs from " << expected.filename().string() << ":\n" << diff);
}

// One test case per golden case, registered as TEST_CASE registers its own, so that CTest lists
// each case (catch_discover_tests sees the cases present when affray_tests was last built).
class CaseInvoker : public Catch::ITestInvoker {
  public:
    explicit CaseInvoker(fs::path file) : m_file(std::move(file)) {}
    void invoke() const override { CheckCase(m_file); }

  private:
    fs::path m_file;
};

const bool g_casesRegistered = [] {
    for (const fs::path& file : ListCases(GoldenDir())) {
        const std::string name = "golden: " + file.filename().string();  // copied by Catch
        Catch::AutoReg(new CaseInvoker(file), CATCH_INTERNAL_LINEINFO, Catch::StringRef(),
                       Catch::NameAndTags(name, "[golden][case]"));
    }
    return true;
}();

}  // namespace

TEST_CASE("golden: the directory holds enough cases, each with a header and an .expected file", "[golden]") {
    const std::vector<fs::path> cases = ListCases(GoldenDir());
    CHECK(cases.size() >= kMinCases);
    for (const fs::path& file : cases) {
        INFO(file.filename().string());
        CHECK(fs::exists(ExpectedPath(file)));
        CHECK(HeaderArgs(affray::test::ReadText(file)).has_value());
    }
    // An .expected file without its case is a case that was renamed or deleted by half.
    for (const fs::directory_entry& entry : fs::directory_iterator(GoldenDir())) {
        if (entry.path().extension() != ".expected") continue;
        INFO(entry.path().filename().string());
        CHECK((fs::exists(fs::path(entry.path()).replace_extension(".sl")) ||
               fs::exists(fs::path(entry.path()).replace_extension(".rib"))));
    }
}

TEST_CASE("golden: the header gives the command line, with the case after the subcommand", "[golden]") {
    CHECK_FALSE(HeaderArgs("displacement d() {}\n").has_value());
    CHECK_FALSE(HeaderArgs("// golden:\n").has_value());
    CHECK_FALSE(HeaderArgs("\n// golden: compile\n").has_value());  // the first line only
    const auto header = HeaderArgs("// golden: eval --mode affine\t--region 0,1,0,1\ndisplacement d() {}\n");
    REQUIRE(header.has_value());
    CHECK(*header == std::vector<std::string>{"eval", "--mode", "affine", "--region", "0,1,0,1"});
    CHECK(CommandFor("d.sl", *header, "/t") ==
          std::vector<std::string>{"eval", "d.sl", "--mode", "affine", "--region", "0,1,0,1"});
    // A render writes its image in the temporary directory, unless the case names one.
    CHECK(CommandFor("s.rib", {"render"}, "/t") == std::vector<std::string>{"render", "s.rib", "-o", "/t/s.exr"});
    CHECK(CommandFor("s.rib", {"render", "-o", "x.exr"}, "/t") ==
          std::vector<std::string>{"render", "s.rib", "-o", "x.exr"});
}

TEST_CASE("golden: a wrong expectation is reported as a mismatch with a diff", "[golden]") {
    // The driver's own comparison can fail: a real case's output against a doctored expectation.
    const std::vector<fs::path> cases = ListCases(GoldenDir());
    REQUIRE_FALSE(cases.empty());
    const fs::path& file = cases.front();
    affray::test::TempDir tmp;
    std::string problem;
    const std::string actual = Actual(file, fs::path(tmp.Path("stdout")).parent_path(), &problem);
    REQUIRE(problem.empty());
    CHECK(Mismatch(affray::test::ReadText(ExpectedPath(file)), actual).empty());
    const size_t status = actual.rfind("--- exit ");
    REQUIRE(status != std::string::npos);
    const std::string wrong = actual.substr(0, status) + "--- exit 42\n";
    const std::string diff = Mismatch(wrong, actual);
    INFO(diff);
    CHECK(diff.find("\n---- exit 42\n") != std::string::npos);
    CHECK(diff.find("\n+" + actual.substr(status)) != std::string::npos);
    CHECK(diff.rfind("--- expected\n+++ actual\n@@ -", 0) == 0);

    // Hunks: a changed line in the middle of a long text shows 3 lines of context either side.
    std::string before, after;
    for (int k = 1; k <= 20; ++k) {
        before += "line " + std::to_string(k) + "\n";
        after += (k == 10 ? "LINE 10" : "line " + std::to_string(k)) + "\n";
    }
    CHECK(Mismatch(before, after) ==
          "--- expected\n+++ actual\n@@ -7,7 +7,7 @@\n line 7\n line 8\n line 9\n-line 10\n+LINE 10\n line 11\n"
          " line 12\n line 13\n");
    CHECK(Mismatch("a\nb\n", "a\n").find("@@ -1,2 +1,1 @@\n a\n-b\n") != std::string::npos);
    CHECK(Mismatch("a\n", "a") == "--- expected\n+++ actual\n@@ -1,1 +1,1 @@\n-a\n+a\\ (no newline at end)\n");
    CHECK(Mismatch("same\n", "same\n").empty());
}

TEST_CASE("golden: MESSAGES.md maps each message to cases that show it", "[golden]") {
    // Each table row is "| source | `message` | case, case |", "…" standing for the variable
    // parts: some line of each case's .expected must hold the literal parts in order.
    std::istringstream doc(affray::test::ReadText(GoldenDir() / "MESSAGES.md"));
    const std::string ellipsis = "\xE2\x80\xA6";
    int rows = 0;
    for (std::string row; std::getline(doc, row);) {
        if (row.rfind("| ", 0) != 0) continue;
        std::vector<std::string> cells;
        for (size_t at = 1, bar; (bar = row.find(" |", at)) != std::string::npos; at = bar + 2)
            cells.push_back(row.substr(at + 1, bar - at - 1));
        const size_t open = cells.size() == 3 ? cells[1].find('`') : std::string::npos;
        if (open == std::string::npos) continue;  // the header row
        const std::string message = cells[1].substr(open + 1, cells[1].find('`', open + 1) - open - 1);
        std::vector<std::string> parts;
        for (size_t at = 0;;) {
            const size_t next = message.find(ellipsis, at);
            parts.push_back(message.substr(at, next == std::string::npos ? std::string::npos : next - at));
            if (next == std::string::npos) break;
            at = next + ellipsis.size();
        }
        ++rows;
        std::istringstream cases(cells[2]);
        for (std::string name; std::getline(cases, name, ',');) {
            name.erase(0, name.find_first_not_of(' '));
            INFO("MESSAGES.md: `" << message << "` in " << name);
            const fs::path expected = ExpectedPath(GoldenDir() / name);
            REQUIRE(fs::exists(GoldenDir() / name));
            std::istringstream lines(affray::test::ReadText(expected));
            bool found = false;
            for (std::string line; !found && std::getline(lines, line);) {
                size_t at = 0;
                found = true;
                for (const std::string& part : parts) {
                    at = line.find(part, at);
                    if (at == std::string::npos) {
                        found = false;
                        break;
                    }
                    at += part.size();
                }
            }
            CHECK(found);
        }
    }
    CHECK(rows > 200);
}
