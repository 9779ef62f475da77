// tests/test_util.h: helpers shared by the test files: compiling shader text, evaluating it on
// the unit square in any number type, and listing the shaders in shaders/.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>

#include <sys/wait.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/compile.h"
#include "diag/limits.h"
#include "scene/geometry/surface.h"

namespace affray::test {

/// Sets a limit (diag/limits.h) for one scope, and puts the value it had back after it.
class ScopedLimit {
  public:
    ScopedLimit(diag::Limit limit, int64_t value) : m_limit(limit), m_old(diag::LimitValue(limit)) {
        diag::SetLimit(limit, value);
    }
    ~ScopedLimit() { diag::SetLimit(m_limit, m_old); }
    ScopedLimit(const ScopedLimit&) = delete;
    ScopedLimit& operator=(const ScopedLimit&) = delete;

  private:
    diag::Limit m_limit;
    int64_t m_old;
};

/// A temporary directory, removed at the end of the test.
class TempDir {
  public:
    TempDir() {
        std::string pattern = (std::filesystem::temp_directory_path() / "affray-test-XXXXXX").string();
        REQUIRE(mkdtemp(pattern.data()) != nullptr);
        m_path = pattern;
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    /// Writes `text` to `name` (which may contain subdirectories); returns its full path.
    std::string Write(const std::string& name, const std::string& text) const {
        std::filesystem::path p = m_path / name;
        std::filesystem::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << text;
        return p.string();
    }
    std::string Path(const std::string& name) const { return (m_path / name).string(); }

  private:
    std::filesystem::path m_path;
};

/// True in an AddressSanitizer build. GCC defines __SANITIZE_ADDRESS__; clang 14, which CI's
/// sanitizer build uses, does not, and answers __has_feature(address_sanitizer) instead.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

/// The heaviest property tests take this fraction of their samples under the sanitizers (-O1,
/// several times slower, there to catch memory and undefined behaviour rather than rare
/// regions); the Release suite takes them all.
inline constexpr int kSanitizerDivisor = kSanitized ? 4 : 1;

inline std::string SourceDir() { return AFFRAY_SOURCE_DIR; }

/// The first line of the last diagnostic in `report` ("file: error: message"), "" if none.
inline std::string LastMessage(const diag::Report& report) {
    if (report.all().empty()) return "";
    const std::string text = diag::Format(report.all().back());
    return text.substr(0, text.find('\n'));
}

/// What the `affray` program printed and its exit status (-1 if it did not exit normally).
struct CliOutput {
    int status;
    std::string out;
};

/// Runs a shell command line and captures its stdout; the status is -1 if it did not exit.
inline CliOutput RunShell(const std::string& command) {
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe);
    std::string out;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
    int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

/// Runs the `affray` program with `args` (shell-quoted by the caller); captures its stdout, and
/// its stderr too when `withStderr`.
inline CliOutput RunCli(const std::string& args, bool withStderr = false) {
    return RunShell(std::string(AFFRAY_CLI) + " " + args + (withStderr ? " 2>&1" : " 2>/dev/null"));
}

/// `affray render RIB -o OUT --stats --quiet EXTRA`, which must succeed: its output (the stats line).
inline std::string RenderWithStats(const std::string& rib, const std::string& out, const std::string& extra = "") {
    const CliOutput r = RunCli("render " + rib + " -o " + out + " --stats --quiet " + extra, true);
    INFO(r.out);
    REQUIRE(r.status == 0);
    return r.out;
}

/// The RMSE `affray diff REFERENCE TEST` reports.
inline double DiffRmse(const std::string& reference, const std::string& test) {
    const CliOutput diff = RunCli("diff " + reference + " " + test);
    INFO(diff.out);
    const size_t at = diff.out.find("\"rmse\":");
    REQUIRE(at != std::string::npos);
    return std::stod(diff.out.substr(at + 7));
}

/// `s` in single quotes, for a RunCli command line (test paths hold no quote).
inline std::string Quote(const std::string& s) { return "'" + s + "'"; }

/// The CLI tests' scene: a patch rippled by shaders/wave.sl with a sphere in front of it, lit,
/// width x height, Display `display` with every AOV; `options` (e.g. a PixelSamples line) go
/// before the camera. The caller copies wave.sl beside it.
inline std::string WaveSphereScene(int width, int height, const std::string& display, const std::string& options = "",
                                   const std::string& color = "0.85 0.62 0.35") {
    return "Format " + std::to_string(width) + " " + std::to_string(height) + " 1\n" + options +
           "Projection \"perspective\" \"fov\" [40]\n"
           "Display \"" +
           display + R"(" "file" "rgba,Z,N,P,st,cost,err"
Translate 0 0 3.1
Rotate -130 1 0 0
WorldBegin
  LightSource "ambientlight" 1 "intensity" [0.06]
  LightSource "distantlight" 2 "intensity" [1.1] "from" [-3 1.5 1.1] "to" [0 0 0]
  Color [)" +
           color +
           R"(]
  Surface "plastic"
  AttributeBegin
    Displacement "wave" "Km" [0.06] "frequency" [6] "decay" [2.5]
    Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]
  AttributeEnd
  AttributeBegin
    Color [0.3 0.5 0.9]
    Translate 0.3 0.2 0.35
    Sphere 0.3 -0.3 0.3 360
  AttributeEnd
WorldEnd
)";
}

/// The whole text of a file ("" if it cannot be read).
inline std::string ReadText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Rewrites the RIB file's `Format` line with a resolution `divisor` times smaller (rounded up, at
/// least minWidth x minHeight), so that a test can render a full scene cheaply. Returns the text.
inline std::string ShrinkFormat(const std::filesystem::path& rib, int divisor, int minWidth = 1, int minHeight = 1) {
    // (Parsed by hand: std::regex trips GCC 12's -Wmaybe-uninitialized in the -O1 ASan build.)
    std::string text = ReadText(rib);
    const size_t format = text.find("\nFormat ");
    REQUIRE(format != std::string::npos);
    const size_t end = text.find('\n', format + 1);
    int w = 0, h = 0;
    std::istringstream(text.substr(format + 8, end - format - 8)) >> w >> h;
    REQUIRE((w > 0 && h > 0));
    w = std::max(minWidth, (w + divisor - 1) / divisor);
    h = std::max(minHeight, (h + divisor - 1) / divisor);
    text.replace(format + 1, end - format - 1, "Format " + std::to_string(w) + " " + std::to_string(h) + " 1");
    std::ofstream(rib, std::ios::binary) << text;
    return text;
}

/// Requires `got` to equal `want` within 1e-12 per component, printing both on failure.
inline void RequireVec(const glm::dvec3& got, const glm::dvec3& want) {
    INFO("got [" << got.x << " " << got.y << " " << got.z << "], want [" << want.x << " " << want.y << " " << want.z
                 << "]");
    REQUIRE(got.x == Approx(want.x).margin(1e-12));
    REQUIRE(got.y == Approx(want.y).margin(1e-12));
    REQUIRE(got.z == Approx(want.z).margin(1e-12));
}

/// The .sl files in shaders/ of one kind, sorted: the displacement shaders (every bound test's
/// subjects), or "surface" or "light" shaders (the standard ones, RI Spec 3.2 appendix A). A
/// file's kind is the first word of its line that starts with one.
inline std::vector<std::string> AllShaders(const std::string& kind = "displacement") {
    std::vector<std::string> paths;
    for (const auto& entry : std::filesystem::directory_iterator(SourceDir() + "/shaders")) {
        if (entry.path().extension() != ".sl") continue;
        std::ifstream in(entry.path());
        std::string fileKind = "displacement", line;
        while (std::getline(in, line)) {
            bool found = false;
            for (const char* k : {"surface ", "light ", "displacement "})
                if (line.rfind(k, 0) == 0) {
                    fileKind = std::string(k, std::strlen(k) - 1);
                    found = true;
                }
            if (found) break;
        }
        if (fileKind == kind) paths.push_back(entry.path().string());
    }
    std::sort(paths.begin(), paths.end());
    return paths;
}

/// Compiles a shader body given as text; throws with the diagnostics if it does not compile.
inline compiler::CompiledShader CompileOrThrow(const std::string& source,
                                               const std::vector<compiler::ParamOverride>& params = {}) {
    compiler::CompileResult r = compiler::CompileSource("test.sl", source, params);
    if (!r.ok()) throw std::runtime_error("does not compile:\n" + r.diagnostics.format());
    return *r.shader;
}

/// Runs `program` with number type N over [u0,u1] x [v0,v1] of `surface`; returns output `name`
/// (P or N).
template <class N>
vm::Vec3<N> EvalOnSurface(const vm::Program& program, const renderer::BaseSurface& surface, double u0, double u1,
                          double v0, double v1, const char* name = "P") {
    vm::Interpreter<N> interp(program);
    return renderer::EvaluateOnSurface(interp, surface, u0, u1, v0, v1, glm::dvec3(0.0), *program.findOutput(name));
}

/// EvalOnSurface on the unit square.
template <class N>
vm::Vec3<N> EvalOnSquare(const vm::Program& program, double u0, double u1, double v0, double v1,
                         const char* name = "P") {
    return EvalOnSurface<N>(program, renderer::BilinearPatch::UnitSquare(), u0, u1, v0, v1, name);
}

/// The displaced P at one point of `surface`, in doubles (through duals if the program takes
/// derivatives).
inline glm::dvec3 PointOnSurface(const vm::Program& program, const renderer::BaseSurface& surface, double u, double v,
                                 const char* name = "P") {
    if (program.usesDerivatives()) {
        auto p = EvalOnSurface<vm::Dual<double>>(program, surface, u, u, v, v, name);
        return {p.x.v, p.y.v, p.z.v};
    }
    auto p = EvalOnSurface<double>(program, surface, u, u, v, v, name);
    return {p.x, p.y, p.z};
}

/// PointOnSurface on the unit square.
inline glm::dvec3 PointOnSquare(const vm::Program& program, double u, double v, const char* name = "P") {
    return PointOnSurface(program, renderer::BilinearPatch::UnitSquare(), u, v, name);
}

}  // namespace affray::test
