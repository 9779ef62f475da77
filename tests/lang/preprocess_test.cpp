// tests/lang/preprocess_test.cpp: the preprocessor (lang/preprocess.*) and diagnostics across files
// (lang/diagnostics.*, PreprocessAndParse in lang/parse.*). Files are written to a fresh temporary
// directory per test; outputs and messages are compared exactly.
#include <catch2/catch.hpp>

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "lang/parse.h"
#include "lang/preprocess.h"
#include "tests/test_util.h"

// lang/preprocess.cpp's wrappers of mcpp's allocation functions (lang/CMakeLists.txt).
extern "C" void* AffrayMcppMalloc(size_t size);
extern "C" void* AffrayMcppRealloc(void* old, size_t size);
extern "C" void AffrayMcppFree(void* p);

namespace affray::lang {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

// The preprocessed text without line markers and blank lines, for comparing expansions.
std::string Code(const PreprocessResult& r) {
    std::string out;
    size_t pos = 0;
    while (pos < r.text.size()) {
        size_t end = r.text.find('\n', pos);
        if (end == std::string::npos) end = r.text.size();
        std::string line = r.text.substr(pos, end - pos);
        pos = end + 1;
        if (line.rfind("#line ", 0) == 0 || line.find_first_not_of(" \t") == std::string::npos) continue;
        out += line + "\n";
    }
    return out;
}

// Each diagnostic as "file:line: message".
std::string Messages(const PreprocessResult& r) {
    std::string out;
    for (const diag::Diagnostic& d : r.errors)
        out += d.where.file + ":" + std::to_string(d.where.line) + ": " + d.message + "\n";
    return out;
}

PreprocessResult Run(const TempDir& dir, const std::string& name, const std::string& text,
                     const PreprocessOptions& options = {}) {
    std::string path = dir.Write(name, text);
    return Preprocess(path, text, options);
}

struct Compiled {
    TranslationUnit unit;
    std::string errors;
    int errorCount = 0;
};

// PreprocessAndParse on the file `name`, as the compiler calls it.
Compiled Parse(const TempDir& dir, const std::string& name, const std::string& text,
               const PreprocessOptions& options = {}) {
    SourceFile file(dir.Write(name, text), text);
    Diagnostics diags(file);
    Compiled out;
    out.unit = PreprocessAndParse(diags, options);
    out.errors = diags.format();
    out.errorCount = diags.errorCount();
    return out;
}

TEST_CASE("object-like and function-like macros expand", "[lang][preprocess]") {
    TempDir dir;
    PreprocessResult r = Run(dir, "m.sl",
                             "#define snoise(x) (2*noise(x)-1)\n"
                             "#define AMP 0.5\n"
                             "f = AMP * snoise(P*4);\n");
    REQUIRE(r.ok);
    CHECK(r.errors.empty());
    CHECK(Code(r) == "f =  0.5  *  (2*noise(P*4)-1) ;\n");

    Compiled c = Parse(dir, "d.sl",
                       "#define snoise(x) (2*noise(x)-1)\n"
                       "displacement d(float Km = .1) {\n"
                       "    P += Km * snoise(P) * normalize(N);\n"
                       "}\n");
    CHECK(c.errors == "");
    REQUIRE(c.unit.shaders.size() == 1);
    CHECK(c.unit.shaders[0].body.at(0)->loc.line == 3);
}

TEST_CASE("#if 0 hides code that would not compile", "[lang][preprocess]") {
    TempDir dir;
    Compiled c = Parse(dir, "d.sl",
                       "#if 0\n"
                       "this is not { RSL at all ;;\n"
                       "#endif\n"
                       "displacement d() { P += 0; }\n");
    CHECK(c.errors == "");
    CHECK(c.unit.shaders.size() == 1);
}

TEST_CASE("#ifdef, #ifndef, #elif and #else pick branches", "[lang][preprocess]") {
    TempDir dir;
    const std::string text =
        "#ifdef BMRT\nbmrt\n#else\nnot_bmrt\n#endif\n"
        "#ifndef PRMAN\nnot_prman\n#endif\n"
        "#if LEVEL == 1\none\n#elif LEVEL == 2\ntwo\n#else\nother\n#endif\n";
    CHECK(Code(Run(dir, "a.sl", text)) == "not_bmrt\nnot_prman\nother\n");

    PreprocessOptions options;
    options.defines = {"BMRT", "PRMAN=1", "LEVEL=2"};
    PreprocessResult r = Run(dir, "b.sl", text, options);
    REQUIRE(r.ok);
    CHECK(Code(r) == "bmrt\ntwo\n");
}

TEST_CASE("defines from the options, NAME=VALUE and NAME, define macros", "[lang][preprocess]") {
    TempDir dir;
    PreprocessOptions options;
    options.defines = {"SCALE=2.5", "FLAG"};
    PreprocessResult r = Run(dir, "a.sl", "x = SCALE * FLAG;\n", options);
    REQUIRE(r.ok);
    CHECK(Code(r) == "x =  2.5  *  1 ;\n");

    options.defines = {"=3"};
    r = Run(dir, "b.sl", "x;\n", options);
    CHECK_FALSE(r.ok);
    CHECK(Messages(r) == dir.Path("b.sl") + ":0: invalid macro definition '-D =3'\n");
}

TEST_CASE("no compiler-specific macros are predefined", "[lang][preprocess]") {
    TempDir dir;
    PreprocessResult r = Run(dir, "a.sl",
                             "__GNUC__ __x86_64__ __amd64__ __linux__ linux unix __MCPP "
                             "__STDC_HOSTED__ __LINE__ __FILE__\n");
    REQUIRE(r.ok);
    CHECK(Code(r) ==
          "__GNUC__ __x86_64__ __amd64__ __linux__ linux unix __MCPP __STDC_HOSTED__"
          "  1   \"" +
              dir.Path("a.sl") + "\"\n");
}

TEST_CASE("#pragma passes through to the lexer, which ignores it", "[lang][preprocess]") {
    TempDir dir;
    // mcpp obeys `#pragma once` itself and passes other pragmas on.
    PreprocessResult r = Run(dir, "a.sl", "#pragma once\n#pragma nolint\nx;\n");
    REQUIRE(r.ok);
    CHECK(Code(r) == "#pragma nolint\nx;\n");
    CHECK(Parse(dir, "d.sl", "#pragma once\ndisplacement d() {}\n").errors == "");
}

TEST_CASE("#include finds files next to the includer, then in includeDirs", "[lang][preprocess]") {
    TempDir dir;
    dir.Write("src/near.h", "#define NEAR 1\n#include \"sub/nested.h\"\n");
    dir.Write("src/sub/nested.h", "nested_line\n");
    dir.Write("lib/far.h", "#define FAR 2\n");
    // The same name in includeDirs loses to the one next to the includer.
    dir.Write("lib/near.h", "#define NEAR 99\n");
    PreprocessOptions options;
    options.includeDirs = {dir.Path("lib")};
    PreprocessResult r = Run(dir, "src/a.sl", "#include \"near.h\"\n#include \"far.h\"\nx = NEAR + FAR;\n", options);
    REQUIRE(r.ok);
    CHECK(Code(r) == "nested_line\nx =  1  +  2 ;\n");
    // Every line marker names a file that exists, so diagnostics can show its lines.
    CHECK(r.text == "#line 1 \"" + dir.Path("src/a.sl") + "\"\n" + "#line 1 \"" + dir.Path("src/near.h") + "\"\n" +
                        "#line 2 \"" + dir.Path("src/near.h") + "\"\n" + "#line 1 \"" + dir.Path("src/sub/nested.h") +
                        "\"\n" + "nested_line\n" + "#line 3 \"" + dir.Path("src/near.h") + "\"\n" + "#line 2 \"" +
                        dir.Path("src/a.sl") + "\"\n" + "#line 1 \"" + dir.Path("lib/far.h") + "\"\n" + "#line 3 \"" +
                        dir.Path("src/a.sl") + "\"\n" + "x =  1  +  2 ;\n");
}

TEST_CASE("a missing #include is an error at its line", "[lang][preprocess]") {
    TempDir dir;
    PreprocessResult r = Run(dir, "a.sl", "x;\n#include \"nowhere.h\"\n");
    CHECK_FALSE(r.ok);
    CHECK(Messages(r) == dir.Path("a.sl") + ":2: Can't open include file \"nowhere.h\"\n");

    Compiled c = Parse(dir, "d.sl", "\n  #include \"nowhere.h\"\ndisplacement d() {}\n");
    CHECK(c.errors == dir.Path("d.sl") +
                          ":2:3: error: Can't open include file \"nowhere.h\"\n"
                          "      #include \"nowhere.h\"\n"
                          "      ^\n");
    CHECK(c.unit.shaders.empty());
}

TEST_CASE("a recursive #include is an error, not a hang", "[lang][preprocess]") {
    TempDir dir;
    // Two self-includes per level would take 2^64 steps without the include-depth limit, which
    // stops the preprocessor at the first #include past it.
    dir.Write("r.h", "#include \"r.h\"\n#include \"r.h\"\n");
    PreprocessResult r = Run(dir, "a.sl", "#include \"r.h\"\n");
    CHECK_FALSE(r.ok);
    CHECK(Messages(r) == dir.Path("r.h") +
                             ":1: #include nested more than 64 files deep: does a header include itself? "
                             "(limit include-depth = 64; raise it with --limit include-depth=N)\n");
    {
        // Up to mcpp's own limit of 256 (the largest include-depth is 200).
        affray::test::ScopedLimit deep(affray::diag::Limit::IncludeDepth, 200);
        CHECK(Messages(Run(dir, "a.sl", "#include \"r.h\"\n")).find("more than 200 files deep") != std::string::npos);
    }

    // The preprocessor stops with the files still open; Preprocess closes them.
    auto openFiles = [] { return std::distance(fs::directory_iterator("/proc/self/fd"), fs::directory_iterator()); };
    if (fs::exists("/proc/self/fd")) {
        auto before = openFiles();
        for (int i = 0; i < 8; ++i) Run(dir, "a.sl", "#include \"r.h\"\n");
        CHECK(openFiles() == before);
    }
}

TEST_CASE("the include-depth limit counts nested files exactly", "[lang][preprocess]") {
    TempDir dir;
    // a.sl includes h1.h, which includes h2.h, ... h5.h: five files deep.
    for (int i = 1; i < 5; ++i)
        dir.Write("h" + std::to_string(i) + ".h", "#include \"h" + std::to_string(i + 1) + ".h\"\n");
    dir.Write("h5.h", "float five = 5;\n");
    {
        affray::test::ScopedLimit limit(affray::diag::Limit::IncludeDepth, 5);
        PreprocessResult r = Run(dir, "a.sl", "#include \"h1.h\"\n");
        CHECK(r.ok);
        CHECK(r.text.find("float five = 5;") != std::string::npos);
    }
    affray::test::ScopedLimit limit(affray::diag::Limit::IncludeDepth, 4);
    PreprocessResult r = Run(dir, "a.sl", "#include \"h1.h\"\n");
    CHECK_FALSE(r.ok);
    CHECK(Messages(r) == dir.Path("h4.h") +
                             ":1: #include nested more than 4 files deep: does a header include itself? "
                             "(limit include-depth = 4; raise it with --limit include-depth=N)\n");
}

TEST_CASE("preprocessed text longer than the source-bytes limit is an error", "[lang][preprocess]") {
    TempDir dir;
    affray::test::ScopedLimit limit(affray::diag::Limit::SourceBytes, 4096);
    // 4^6 copies of a 10-byte line: 40 KB of output from 200 bytes of macros.
    const std::string text =
        "#define A x = 1 + 2;\n#define B A A A A\n#define C B B B B\n#define D C C C C\n"
        "#define E D D D D\n#define F E E E E\n#define G F F F F\nG\n";
    PreprocessResult r = Run(dir, "a.sl", text);
    CHECK_FALSE(r.ok);
    CHECK(Messages(r).find("preprocessed text longer than 4096 bytes") != std::string::npos);
    CHECK(Messages(r).find("(limit source-bytes = 4096; raise it with --limit source-bytes=N)") != std::string::npos);
    // And a source over the limit is refused before mcpp runs.
    CHECK(Messages(Run(dir, "b.sl", std::string(5000, ' '))) ==
          dir.Path("b.sl") +
              ":0: file larger than 4096 bytes (limit source-bytes = 4096; raise it with --limit "
              "source-bytes=N)\n");
}

TEST_CASE("an unterminated #if is an error", "[lang][preprocess]") {
    TempDir dir;
    PreprocessResult r = Run(dir, "a.sl", "#if 1\nx;\n#ifdef Y\n");
    CHECK_FALSE(r.ok);
    CHECK(Messages(r) == dir.Path("a.sl") + ":3: End of input within #if (#ifdef) section started at line 1\n");
}

TEST_CASE("a syntax error in a header names the header", "[lang][preprocess]") {
    TempDir dir;
    dir.Write("inc/body.h", "// the shader\ndisplacement d() {\n    P += 1\n}\n");
    PreprocessOptions options;
    options.includeDirs = {dir.Path("inc")};
    Compiled c = Parse(dir, "d.sl", "#define UNUSED 1\n#include \"body.h\"\n", options);
    CHECK(c.errors == dir.Path("inc/body.h") +
                          ":4:1: error: syntax error, unexpected '}', expecting ';'\n"
                          "    }\n"
                          "    ^\n");
}

TEST_CASE("a syntax error after an #include is at its line of the main file", "[lang][preprocess]") {
    TempDir dir;
    dir.Write("defs.h", "#define K 2\n\n\n#define J 3\n");
    Compiled c = Parse(dir, "d.sl",
                       "#include \"defs.h\"\n"
                       "displacement d() {\n"
                       "    float a = K;\n"
                       "    float b = a +;\n"
                       "}\n");
    CHECK(c.errors == dir.Path("d.sl") +
                          ":4:18: error: syntax error, unexpected ';'\n"
                          "        float b = a +;\n"
                          "                     ^\n");
}

TEST_CASE("bad input never crashes or prints", "[lang][preprocess]") {
    TempDir dir;
    for (const std::string& text : {std::string("#define\n#if\n#elif\n#endif\n#endif\n#include\n#include <>\n"),
                                    std::string("#define f(x x\nf(\n#undef\n#line 0\n#error stop\n"),
                                    std::string("\x7F"
                                                "ELF\x02\x00\x01\xFF#\n\"unterminated\n",
                                                18),
                                    std::string("#define A A B\n#define B A\nA B\n")}) {
        PreprocessResult r = Run(dir, "g.sl", text);
        if (!r.ok) CHECK_FALSE(r.errors.empty());
    }
    PreprocessResult r = Run(dir, "e.sl", "#error stop here\n");
    CHECK_FALSE(r.ok);
    CHECK(Messages(r) == dir.Path("e.sl") + ":1: #error stop here\n");
}

TEST_CASE("preprocessing from several threads takes turns", "[lang][preprocess]") {
    TempDir dir;
    std::vector<std::string> outputs(8);
    std::vector<std::thread> threads;
    for (size_t i = 0; i < outputs.size(); ++i)
        threads.emplace_back([&, i] {
            PreprocessOptions options;
            options.defines = {"N=" + std::to_string(i)};
            outputs[i] = Code(Preprocess(dir.Path("t.sl"), "x = N;\n", options));
        });
    for (std::thread& t : threads) t.join();
    for (size_t i = 0; i < outputs.size(); ++i) CHECK(outputs[i] == "x =  " + std::to_string(i) + " ;\n");
}

// Found by fuzz_sl (fuzz/regressions/fuzz_sl/mcpp_memcmp_long_identifier.sl): mcpp looks a name up
// in its macro table with memcmp over the name's whole length, past the end of a shorter name
// in the table; AddressSanitizer reported the read (lang/preprocess.cpp's AffrayMcppMemcmp stops
// at the first difference). Names long and short, alone and next to macros of their hash chain.
TEST_CASE("long identifiers are looked up within mcpp's buffers", "[lang][preprocess]") {
    TempDir dir;
    const std::vector<std::string> texts = {"BRmfffffffffffffffffffffiif",
                                            "#define A 1\n" + std::string(200, 'A') + " A\n",
                                            "#define " + std::string(70, 'x') + " 2\n" + std::string(71, 'x') + "\n"};
    for (const std::string& text : texts) {
        INFO(text);
        PreprocessResult r = Run(dir, "m.sl", text);
        CHECK(r.ok);
        CHECK(r.errors.empty());
    }
    PreprocessResult r = Run(dir, "m.sl", "BRmfffffffffffffffffffffiif");
    CHECK(Code(r) == "BRmfffffffffffffffffffffiif\n");
}

// mcpp's xrealloc takes a null result for success when the size is 0, and glibc's realloc(p, 0)
// frees p and returns null: mcpp kept p, and lang/preprocess.cpp's tracking freed it a second
// time after the run (a crash of `affray compile`). The wrapper mcpp calls keeps a block instead.
TEST_CASE("mcpp's realloc to zero bytes keeps a block", "[lang][preprocess]") {
    void* p = AffrayMcppMalloc(32);
    REQUIRE(p);
    void* q = AffrayMcppRealloc(p, 0);
    CHECK(q != nullptr);
    AffrayMcppFree(q);
    // And during a run, where the blocks are tracked: macros with empty arguments and bodies.
    TempDir dir;
    PreprocessResult r = Run(dir, "m.sl", "#define E()\n#define F(a, b) a b\nE() F(,) F(E(),) x\n");
    CHECK(r.ok);
    CHECK(Code(r).find('x') != std::string::npos);
}

}  // namespace
}  // namespace affray::lang
